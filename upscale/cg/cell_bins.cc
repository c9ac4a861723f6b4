#include "upscale/cg/cell_bins.h"

#include <algorithm>
#include <limits>

#include "dem/core/error.h"

namespace upgrain::upscale::cg {

CellBins::CellBins(std::span<const Vec3> positions, double cell_size) {
  if (!(cell_size > 0.0)) throw Error("coarse graining: cell size must be positive");
  inv_h_ = 1.0 / cell_size;
  if (positions.empty()) return;
  std::array<long, 3> hi{};
  lo_.fill(std::numeric_limits<long>::max());
  hi.fill(std::numeric_limits<long>::min());
  std::vector<std::array<long, 3>> cell(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(positions[i][d])) throw Error("coarse graining: a position is not finite");
      cell[i][d] = static_cast<long>(std::floor(positions[i][d] * inv_h_));
      lo_[d] = std::min(lo_[d], cell[i][d]);
      hi[d] = std::max(hi[d], cell[i][d]);
    }
  for (int d = 0; d < 3; ++d) n_[d] = hi[d] - lo_[d] + 1;
  const long cells = n_[0] * n_[1] * n_[2];
  if (cells > 64L * static_cast<long>(positions.size()) + (1L << 20))
    throw Error("coarse graining: the items spread over too many cells of the kernel's size");
  std::vector<int> linear(positions.size());
  start_.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    linear[i] = static_cast<int>(((cell[i][2] - lo_[2]) * n_[1] + (cell[i][1] - lo_[1])) * n_[0] +
                                 (cell[i][0] - lo_[0]));
    ++start_[linear[i] + 1];
  }
  for (long c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  items_.resize(positions.size());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < positions.size(); ++i) items_[fill[linear[i]]++] = static_cast<int>(i);
}

}  // namespace upgrain::upscale::cg
