#include "dem/neighbor/verlet_list.h"

#include <algorithm>
#include <numeric>

namespace upgrain::dem {

namespace {

// The bounding box of every local particle.
void bounds(const ParticleStore& p, Vec3& lo, Vec3& hi) {
  lo = hi = Vec3::Zero();
  if (p.size() == 0) return;
  lo = hi = p.x[0];
  for (std::size_t i = 1; i < p.size(); ++i) {
    lo = lo.cwiseMin(p.x[i]);
    hi = hi.cwiseMax(p.x[i]);
  }
}

// Calls visit(j) for every local particle j in the 27 cells around owned particle i.
template <class Visit>
void for_stencil(const CellGrid& grid, const Vec3& xi, Visit visit) {
  const std::vector<int>& start = grid.cell_start();
  const std::vector<int>& order = grid.order();
  const auto& dims = grid.dims();
  const auto c = grid.cell_coords(xi);
  for (int z = std::max(c[2] - 1, 0); z <= std::min(c[2] + 1, dims[2] - 1); ++z)
    for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims[1] - 1); ++y)
      for (int x = std::max(c[0] - 1, 0); x <= std::min(c[0] + 1, dims[0] - 1); ++x) {
        const int cell = grid.flat(x, y, z);
        for (int s = start[cell]; s < start[cell + 1]; ++s) visit(order[s]);
      }
}

}  // namespace

bool evaluates_across_ranks(GlobalId mine, GlobalId other) {
  // The owner of the lower id when the ids' sum is even, of the higher one when it is odd:
  // either rank may hold either particle, so the pairs across a cut split about evenly, where
  // "the lower id" alone would give them all to one side when ids grow across the cut.
  const bool even = ((mine + other) & 1) == 0;
  return even ? mine < other : mine > other;
}

VerletList::VerletList(double max_radius, double skin, PairOrder order)
    : cell_size_(2.0 * max_radius + skin), skin_(skin), order_(order) {}

void VerletList::build(const ParticleStore& p, int n_owned, const std::vector<PlaneWall>& walls) {
  Vec3 lo, hi;
  bounds(p, lo, hi);
  grid_ = CellGrid(lo, hi, cell_size_, 4L * static_cast<long>(p.size()) + 64);
  grid_.bin(p.x);
  if (order_ == PairOrder::local)
    build_local(p, n_owned);
  else
    build_global_id(p, n_owned);
  // The list's size changes little between builds: drop the slack of the first build's
  // doubling growth once (part of the peak memory per grain of the dense-bed benchmark).
  if (pairs_.partner.capacity() > pairs_.partner.size() + pairs_.partner.size() / 8)
    pairs_.partner.shrink_to_fit();
  slots_per_owned_.assign(static_cast<std::size_t>(n_owned), 0);
  for (std::size_t r = 0; r < pairs_.num_rows(); ++r) {
    const int i = pairs_.row_particle[r];
    for (int k = pairs_.row_start[r]; k < pairs_.row_start[r + 1]; ++k) {
      if (i < n_owned) ++slots_per_owned_[i];
      if (pairs_.partner[k] < n_owned) ++slots_per_owned_[pairs_.partner[k]];
    }
  }
  build_walls(p, n_owned, walls);
  x_at_build_.assign(p.x.begin(), p.x.begin() + n_owned);
  ++builds_;
}

bool VerletList::needs_rebuild(const ParticleStore& p) const {
  const double limit2 = rebuild_displacement2();
  for (std::size_t i = 0; i < x_at_build_.size(); ++i)
    if ((p.x[i] - x_at_build_[i]).squaredNorm() > limit2) return true;
  return false;
}

void VerletList::build_local(const ParticleStore& p, int n_owned) {
  PairList& l = pairs_;
  l.row_particle.resize(static_cast<std::size_t>(n_owned));
  std::iota(l.row_particle.begin(), l.row_particle.end(), 0);
  l.row_start.assign(static_cast<std::size_t>(n_owned) + 1, 0);
  l.partner.clear();
  for (int i = 0; i < n_owned; ++i) {
    l.row_start[i] = static_cast<int>(l.partner.size());
    const Vec3 xi = p.x[i];
    const double ri = p.radius[i] + skin_;
    const GlobalId gi = p.id[i];
    for_stencil(grid_, xi, [&](int j) {
      if (j < n_owned ? j <= i : !evaluates_across_ranks(gi, p.id[j])) return;
      const double cut = ri + p.radius[j];
      if ((p.x[j] - xi).squaredNorm() < cut * cut) l.partner.push_back(j);
    });
    // Partners in increasing local index: a fixed order of force accumulation.
    std::sort(l.partner.begin() + l.row_start[i], l.partner.end());
  }
  l.row_start[n_owned] = static_cast<int>(l.partner.size());
}

void VerletList::build_global_id(const ParticleStore& p, int n_owned) {
  const int n = static_cast<int>(p.size());
  // 1. Every pair once, from its owned side (an owned pair from its lower id), as (lo, hi).
  std::vector<int> first, second;
  for (int i = 0; i < n_owned; ++i) {
    const Vec3 xi = p.x[i];
    const double ri = p.radius[i] + skin_;
    const GlobalId gi = p.id[i];
    for_stencil(grid_, xi, [&](int j) {
      if (j == i || (j < n_owned && p.id[j] < gi)) return;
      const double cut = ri + p.radius[j];
      if ((p.x[j] - xi).squaredNorm() >= cut * cut) return;
      const bool i_lower = gi < p.id[j];
      first.push_back(i_lower ? i : j);
      second.push_back(i_lower ? j : i);
    });
  }
  // 2. Rows by first particle (counting sort), each sorted by the partner's global id.
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (int f : first) ++start[f + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> by_first(second.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < first.size(); ++k) by_first[fill[first[k]]++] = second[k];
  auto by_id = [&](int a, int b) { return p.id[a] < p.id[b]; };
  std::vector<int> rows;
  for (int f = 0; f < n; ++f) {
    if (start[f + 1] == start[f]) continue;
    std::sort(by_first.begin() + start[f], by_first.begin() + start[f + 1], by_id);
    rows.push_back(f);
  }
  // 3. The rows in order of their first particle's global id.
  std::sort(rows.begin(), rows.end(), by_id);
  PairList& l = pairs_;
  l.row_particle = rows;
  l.row_start.assign(rows.size() + 1, 0);
  l.partner.clear();
  l.partner.reserve(by_first.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    l.row_start[r] = static_cast<int>(l.partner.size());
    l.partner.insert(l.partner.end(), by_first.begin() + start[rows[r]],
                     by_first.begin() + start[rows[r] + 1]);
  }
  l.row_start[rows.size()] = static_cast<int>(l.partner.size());
}

void VerletList::build_walls(const ParticleStore& p, int n_owned, const std::vector<PlaneWall>& walls) {
  walls_.particle.clear();
  walls_.wall.clear();
  auto near = [&](int i, int w) { return walls[w].distance(p.x[i]) < p.radius[i] + skin_; };
  const int nw = static_cast<int>(walls.size());
  if (order_ == PairOrder::local) {
    for (int w = 0; w < nw; ++w)
      for (int i = 0; i < n_owned; ++i)
        if (near(i, w)) walls_.particle.push_back(i), walls_.wall.push_back(w);
  } else {
    for (int i = 0; i < n_owned; ++i)
      for (int w = 0; w < nw; ++w)
        if (near(i, w)) walls_.particle.push_back(i), walls_.wall.push_back(w);
  }
}

void sort_by_cell(ParticleStore& p, double cell_size) {
  const std::size_t n = p.size();
  if (n == 0) return;
  Vec3 lo, hi;
  bounds(p, lo, hi);
  CellGrid grid(lo, hi, cell_size, 4L * static_cast<long>(n) + 64);
  grid.bin(p.x);
  p.permute(grid.order());
}

}  // namespace upgrain::dem
