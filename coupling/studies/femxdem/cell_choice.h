#pragma once
// Which DEM cells of FEM x DEM a scene asks to see (FEMxDEM/cell snapshots; docs/femxdem.md,
// "The study"): every one, or element:point pairs as points.csv numbers them. Plain C++ for the
// input layer's checks and the study's writer (cell_snapshots.h).
#include <string>
#include <utility>
#include <vector>

#include "fem/quasi_static/point_state.h"

namespace upgrain::coupling {

// The element's number is the first of deal.II's cell id ("20_0:" is element 20), the point the
// Gauss point's index in it.
struct CellSnapshotChoice {
  bool all = false;
  std::vector<std::pair<long, unsigned>> points;
  [[nodiscard]] bool empty() const { return !all && points.empty(); }
  [[nodiscard]] bool chooses(const fem::PointPlace& place) const;
};

// Throws upgrain::Error naming the entry's bad item.
CellSnapshotChoice parse_cell_snapshots(const std::string& entry);

// The element's number of a point's cell id.
long element_of(const std::string& cell);

}  // namespace upgrain::coupling
