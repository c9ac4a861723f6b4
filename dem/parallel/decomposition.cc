#include "dem/parallel/decomposition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "dem/core/error.h"

namespace upgrain::dem {

namespace {

// Minimum image (Allen and Tildesley 2017, sec. 1.6.2): with the cell longer than twice the
// interaction range, a grain is in range of at most one image of any other.
void check_periodic_length(int d, double length, double min_block) {
  if (length > 2.0 * min_block) return;
  std::ostringstream m;
  m << "periodic cell: the periodic axis "
    << "xyz"[d] << " is " << length << " m long, not longer than twice the interaction range " << min_block
    << " m (largest diameter + skin); make the cell longer along "
    << "xyz"[d] << " or the grains smaller";
  throw Error(m.str());
}

}  // namespace

std::array<int, 3> choose_blocks(int ranks, const Box& box, double min_block, int unsplit_axis) {
  const Vec3 l = box.hi - box.lo;
  std::array<int, 3> best{0, 0, 0};
  double best_area = std::numeric_limits<double>::infinity();
  // px outermost, pz innermost and a strict '<': among equal areas the first found wins,
  // i.e. the largest px, then the largest py (fewest z cuts, then fewest y cuts).
  for (int px = ranks; px >= 1; --px) {
    if (ranks % px != 0) continue;
    for (int py = ranks / px; py >= 1; --py) {
      if ((ranks / px) % py != 0) continue;
      const int pz = ranks / (px * py);
      const std::array<int, 3> b{px, py, pz};
      bool thin = false;
      for (int d = 0; d < 3; ++d) thin = thin || (b[d] > 1 && l[d] / b[d] < min_block);
      if (thin || (unsplit_axis >= 0 && b[static_cast<std::size_t>(unsplit_axis)] > 1)) continue;
      const double area = (px - 1) * l[1] * l[2] + (py - 1) * l[0] * l[2] + (pz - 1) * l[0] * l[1];
      if (area < best_area) {
        best_area = area;
        best = {px, py, pz};
      }
    }
  }
  if (best[0] == 0) {
    std::ostringstream m;
    m << "domain decomposition: no arrangement of " << ranks << " blocks over the box " << l[0] << " x "
      << l[1] << " x " << l[2] << " m keeps every block at least as thick as the interaction range "
      << min_block << " m (largest diameter + skin); use fewer ranks";
    throw Error(m.str());
  }
  return best;
}

Decomposition::Decomposition(MPI_Comm comm, const Box& box, double min_block, std::array<int, 3> blocks,
                             std::array<bool, 3> periodic, double growth, int unsplit_axis)
    : box_(box), cell_(make_periodic_cell(box, periodic, growth)), min_block_(min_block) {
  box_ = cell_.box;  // the faces of the periodic axes on their grid
  MPI_Comm_size(comm, &size_);
  for (int d = 0; d < 3; ++d) {
    // Minimum image (Allen and Tildesley 2017, sec. 1.6.2): with the cell longer than twice the
    // interaction range, a grain is in range of at most one image of any other, so each pair
    // is one pair, and a ghost layer never reaches a second image.
    if (periodic[d]) check_periodic_length(d, box.hi[d] - box.lo[d], min_block);
  }
  if (blocks[0] <= 0 || blocks[1] <= 0 || blocks[2] <= 0)
    blocks = choose_blocks(size_, box_, min_block, unsplit_axis);
  if (unsplit_axis >= 0 && blocks[static_cast<std::size_t>(unsplit_axis)] != 1) {
    std::ostringstream m;
    m << "domain decomposition: " << blocks[0] << " x " << blocks[1] << " x " << blocks[2]
      << " blocks cut the sheared cell's shear axis "
      << "xyz"[unsplit_axis]
      << ", which must keep one block (its images slide along it: docs/periodic.md, \"Shear\"); set "
         "Parallel/blocks with 1 along it";
    throw Error(m.str());
  }
  const Vec3 l = box_.hi - box_.lo;
  if (blocks[0] * blocks[1] * blocks[2] != size_) {
    std::ostringstream m;
    m << "domain decomposition: " << blocks[0] << " x " << blocks[1] << " x " << blocks[2] << " blocks for "
      << size_ << " MPI ranks; their product must equal the rank count";
    throw Error(m.str());
  }
  for (int d = 0; d < 3; ++d) {
    // One block along an axis has no neighbour along it: any thickness will do.
    if (blocks[d] > 1 && l[d] / blocks[d] < min_block) {
      std::ostringstream m;
      m << "domain decomposition: blocks of " << l[0] / blocks[0] << " x " << l[1] / blocks[1] << " x "
        << l[2] / blocks[2] << " m (" << blocks[0] << " x " << blocks[1] << " x " << blocks[2]
        << " over the box " << l[0] << " x " << l[1] << " x " << l[2] << " m) are thinner along "
        << "xyz"[d] << " than the interaction range " << min_block
        << " m (largest diameter + skin): ghosts would need a second layer of neighbours";
      throw Error(m.str());
    }
  }
  dims_ = blocks;
  const int periods[3] = {periodic[0] ? 1 : 0, periodic[1] ? 1 : 0, periodic[2] ? 1 : 0};
  // reorder = 0: the Cartesian rank is the rank in `comm`, so callers' rank 0 stays rank 0.
  MPI_Cart_create(comm, 3, dims_.data(), periods, 0, &cart_);
  MPI_Comm_rank(cart_, &rank_);
  MPI_Cart_coords(cart_, rank_, 3, coords_.data());
  for (int d = 0; d < 3; ++d) {
    MPI_Cart_shift(cart_, d, 1, &neighbor_[d][0], &neighbor_[d][1]);
    image_shift_[d][0] = periodic[d] && coords_[d] == 0 ? l[d] : 0.0;
    image_shift_[d][1] = periodic[d] && coords_[d] == dims_[d] - 1 ? -l[d] : 0.0;
    planes_[d].resize(static_cast<std::size_t>(dims_[d] + 1));
    for (int k = 0; k <= dims_[d]; ++k) planes_[d][k] = box_.lo[d] + k * (box_.hi[d] - box_.lo[d]) / dims_[d];
  }
  update_block();
}

void Decomposition::update_block() {
  const double inf = std::numeric_limits<double>::infinity();
  for (int d = 0; d < 3; ++d) {
    // A periodic axis has no open faces: its border blocks end at the cell's faces.
    const bool open = !cell_.periodic[d];
    block_.lo[d] = open && coords_[d] == 0 ? -inf : plane(d, coords_[d]);
    block_.hi[d] = open && coords_[d] == dims_[d] - 1 ? inf : plane(d, coords_[d] + 1);
  }
}

void Decomposition::set_cuts(int d, const std::vector<double>& cuts) {
  const int n = dims_[d] - 1;
  std::ostringstream m;
  if (static_cast<int>(cuts.size()) != n) {
    m << "load balance: " << cuts.size() << " cuts along "
      << "xyz"[d] << " for " << dims_[d] << " blocks";
  } else {
    for (int k = 0; k < n && m.tellp() == 0; ++k) {
      const bool inside = cuts[k] >= box_.lo[d] && cuts[k] <= box_.hi[d];
      const bool ascending = k == 0 || cuts[k] >= cuts[k - 1];
      // Interior block k (k = 1 .. n - 1 in cut numbering) lies between cuts k - 1 and k.
      const bool thick = k == 0 || cuts[k] - cuts[k - 1] >= min_block_;
      if (!inside || !ascending || !thick)
        m << "load balance: plane " << k + 1 << " along "
          << "xyz"[d] << " at " << cuts[k] << " m "
          << (!inside      ? "outside the box"
              : !ascending ? "below the previous plane"
                           : "leaves a block thinner")
          << (inside && ascending ? " than the interaction range" : "") << " (box " << box_.lo[d] << " .. "
          << box_.hi[d] << " m, interaction range " << min_block_ << " m)";
    }
  }
  if (m.tellp() != 0) throw Error(m.str());
  for (int k = 0; k < n; ++k) planes_[d][static_cast<std::size_t>(k + 1)] = cuts[k];
  update_block();
}

void Decomposition::deform(const Box& cell_box) {
  if (!grid_holds(cell_, cell_box)) {
    std::ostringstream m;
    m << "periodic cell: the deforming cell " << cell_box.hi - cell_box.lo
      << " m has grown past what its position grid holds (twice its first size along an axis, "
         "docs/periodic.md, \"Exact images\")";
    throw Error(m.str());
  }
  for (int d = 0; d < 3; ++d) {
    if (!cell_.periodic[d]) continue;
    const double lo = cell_box.lo[d], hi = cell_box.hi[d];
    check_periodic_length(d, hi - lo, min_block_);
    const double old_lo = box_.lo[d], scale = (hi - lo) / (box_.hi[d] - old_lo);
    std::vector<double>& p = planes_[d];
    for (std::size_t k = 1; k + 1 < p.size(); ++k) p[k] = lo + (p[k] - old_lo) * scale;
    p.front() = lo;
    p.back() = hi;
    for (std::size_t k = 0; k + 1 < p.size(); ++k) {
      if (p[k + 1] - p[k] >= min_block_) continue;
      std::ostringstream m;
      m << "periodic cell: the deforming cell has shrunk so that a block along "
        << "xyz"[d] << " is " << p[k + 1] - p[k] << " m thick, thinner than the interaction range "
        << min_block_ << " m; run on fewer ranks along "
        << "xyz"[d] << " (Parallel/blocks) or compress less";
      throw Error(m.str());
    }
    box_.lo[d] = cell_.box.lo[d] = lo;
    box_.hi[d] = cell_.box.hi[d] = hi;
    if (image_shift_[d][0] != 0.0) image_shift_[d][0] = hi - lo;
    if (image_shift_[d][1] != 0.0) image_shift_[d][1] = lo - hi;
  }
  update_block();
}

void Decomposition::set_shear(const ShearImages& shear) {
  if (shear.any()) {
    const int s = shear.shear, g = shear.gradient;
    if (s == g || !cell_.periodic[s] || !cell_.periodic[g])
      throw Error("periodic cell: a sheared cell needs its shear and gradient axes distinct and periodic");
    if (dims_[s] != 1)
      throw Error(std::string("periodic cell: the shear axis ") + "xyz"[s] +
                  " of a sheared cell must keep one block");
  }
  cell_.shear = shear;
}

Decomposition::~Decomposition() {
  if (cart_ != MPI_COMM_NULL) MPI_Comm_free(&cart_);
}

std::array<int, 3> Decomposition::block_of(const Vec3& x) const {
  std::array<int, 3> c{};
  for (int d = 0; d < 3; ++d) {
    // The number of interior planes at or below x: compared against the same numbers as
    // the block bounds, so a particle on a plane belongs to exactly one block. The planes
    // need not be equally spaced (load balance).
    const auto first = planes_[d].begin() + 1, last = planes_[d].end() - 1;
    c[d] = static_cast<int>(std::upper_bound(first, last, x[d]) - first);
  }
  return c;
}

int Decomposition::step_towards(int d, int c) const {
  int diff = c - coords_[d];
  if (cell_.periodic[d]) {
    // The shorter way round; with two blocks both ways reach the same neighbour.
    const int n = dims_[d];
    if (diff > n / 2) diff -= n;
    if (diff < -(n / 2)) diff += n;
  }
  return diff > 0 ? 1 : diff < 0 ? -1 : 0;
}

int Decomposition::rank_of_block(const std::array<int, 3>& c) const {
  int r = 0;
  MPI_Cart_rank(cart_, c.data(), &r);
  return r;
}

}  // namespace upgrain::dem
