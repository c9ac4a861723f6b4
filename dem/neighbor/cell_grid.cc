#include "dem/neighbor/cell_grid.h"

#include <algorithm>
#include <cmath>

#include "dem/core/error.h"

namespace upgrain::dem {

CellGrid::CellGrid(const Vec3& lo, const Vec3& hi, double min_cell_size, long max_cells) : lo_(lo) {
  if (!(min_cell_size > 0.0)) throw Error("CellGrid: cell size must be positive");
  double size = min_cell_size;
  for (;;) {
    double total = 1.0;
    for (int d = 0; d < 3; ++d) {
      const double extent = std::max(hi[d] - lo[d], size);
      dims_[d] = std::max(1, static_cast<int>(std::floor(extent / size)));
      inv_size_[d] = dims_[d] / extent;
      total *= dims_[d];
    }
    if (total <= static_cast<double>(max_cells)) break;
    size *= 1.25;
  }
  cell_start_.assign(static_cast<std::size_t>(num_cells()) + 1, 0);
}

std::array<int, 3> CellGrid::cell_coords(const Vec3& p) const {
  std::array<int, 3> c{};
  for (int d = 0; d < 3; ++d) {
    const double s = (p[d] - lo_[d]) * inv_size_[d];
    // NaN compares false and lands in cell 0; the caller checks finiteness separately.
    int i = s > 0.0 ? static_cast<int>(s) : 0;
    c[d] = std::min(i, dims_[d] - 1);
  }
  return c;
}

int CellGrid::cell_index(const Vec3& p) const {
  const auto c = cell_coords(p);
  return flat(c[0], c[1], c[2]);
}

void CellGrid::bin(const std::vector<Vec3>& x) {
  const int n = static_cast<int>(x.size());
  cell_of_.resize(n);
  std::fill(cell_start_.begin(), cell_start_.end(), 0);
  for (int i = 0; i < n; ++i) {
    const int c = cell_index(x[i]);
    cell_of_[i] = c;
    ++cell_start_[c + 1];
  }
  for (int c = 0; c < num_cells(); ++c) cell_start_[c + 1] += cell_start_[c];
  order_.resize(n);
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < n; ++i) order_[fill[cell_of_[i]]++] = i;
}

}  // namespace upgrain::dem
