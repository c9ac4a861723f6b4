#pragma once
// Link cells for the coarse-graining sums (docs/coarse-graining.md, "Cost"): items (grains,
// branch midpoints, wall contacts) binned in cubic cells of a given size aligned with the
// origin, so that a cell is the same cell on every rank whatever part of the state it holds.
// A point visits its 27 cells in a fixed order and each cell's items in their input order
// (id order): the order of every sum depends on the point and the whole state only, which
// makes the fields the same bits on any number of ranks.
#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "upscale/cg/kernel.h"

namespace upgrain::upscale::cg {

class CellBins {
 public:
  // Bins `positions` in cells of edge `cell_size` (> 0): an item interacts with points at
  // most cell_size away from its position.
  CellBins(std::span<const Vec3> positions, double cell_size);

  // Calls f(item) for every item in the 27 cells around r.
  template <class F>
  void for_each_near(const Vec3& r, F&& f) const {
    if (items_.empty()) return;
    long c[3];
    for (int d = 0; d < 3; ++d) c[d] = static_cast<long>(std::floor(r[d] * inv_h_)) - lo_[d];
    for (long k = c[2] - 1; k <= c[2] + 1; ++k) {
      if (k < 0 || k >= n_[2]) continue;
      for (long j = c[1] - 1; j <= c[1] + 1; ++j) {
        if (j < 0 || j >= n_[1]) continue;
        const long row = (k * n_[1] + j) * n_[0];
        const long i0 = std::max(c[0] - 1, 0L), i1 = std::min(c[0] + 1, n_[0] - 1);
        if (i0 > i1) continue;
        // Cells i0..i1 of a row are contiguous: one run of items.
        for (int m = start_[row + i0]; m < start_[row + i1 + 1]; ++m) f(items_[m]);
      }
    }
  }

 private:
  double inv_h_ = 0.0;
  std::array<long, 3> lo_{}, n_{};
  std::vector<int> start_;  // [cell] first entry of items_, one past the last cell at the end
  std::vector<int> items_;  // item indices by cell, in input order within a cell
};

}  // namespace upgrain::upscale::cg
