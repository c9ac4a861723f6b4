#pragma once
// Link cells: a uniform grid of cubic cells no smaller than the interaction range, so
// every contact partner of a particle lies in its own or one of the 26 adjacent cells
// (Yan and Regueiro, section 5; docs/stress.md). Built by a counting sort; positions outside the grid are
// clamped into the border cells, which keeps adjacent particles in adjacent cells.
#include <array>
#include <vector>

#include "dem/core/types.h"

namespace upgrain::dem {

class CellGrid {
 public:
  CellGrid() = default;
  // At most max_cells cells: larger cells stay correct, only slower.
  CellGrid(const Vec3& lo, const Vec3& hi, double min_cell_size, long max_cells = 1L << 24);

  // Bins the positions; afterwards order() lists particle indices cell by cell.
  void bin(const std::vector<Vec3>& x);

  [[nodiscard]] int cell_index(const Vec3& p) const;
  [[nodiscard]] std::array<int, 3> cell_coords(const Vec3& p) const;
  [[nodiscard]] int flat(int ix, int iy, int iz) const { return (iz * dims_[1] + iy) * dims_[0] + ix; }
  [[nodiscard]] const std::array<int, 3>& dims() const { return dims_; }
  [[nodiscard]] int num_cells() const { return dims_[0] * dims_[1] * dims_[2]; }
  [[nodiscard]] const std::vector<int>& cell_start() const { return cell_start_; }
  [[nodiscard]] const std::vector<int>& order() const { return order_; }
  [[nodiscard]] const std::vector<int>& cell_of() const { return cell_of_; }

 private:
  Vec3 lo_ = Vec3::Zero();
  Vec3 inv_size_ = Vec3::Ones();
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> cell_start_;  // size num_cells + 1
  std::vector<int> order_;       // particle indices sorted by cell
  std::vector<int> cell_of_;     // cell of each particle
};

}  // namespace upgrain::dem
