#pragma once
// Cartesian domain decomposition: px x py x pz blocks over a global box, one block per rank
// of an MPI Cartesian communicator, periodic along the periodic axes of the cell
// (docs/periodic.md). Along a bounded axis the outer faces of the border blocks are open: a
// particle outside the box (above the fill, say) belongs to the nearest block, so ownership is
// defined everywhere. Along a periodic axis the box is the cell: the border blocks end at its
// faces, and their neighbours across them are the blocks at the other end (the same rank when
// the axis has one block). The planes start equally spaced; the load balance
// (load_balance.h) moves them per axis, keeping the tensor grid. The block-choice rule is
// in docs/parallel.md.
#include <mpi.h>

#include <array>
#include <vector>

#include "dem/core/box.h"
#include "dem/core/periodic_cell.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// The px x py x pz of least internal cut area, (px-1) Ly Lz + (py-1) Lx Lz + (pz-1) Lx Ly,
// over the factorisations of `ranks` whose blocks are at least `min_block` thick along every
// axis that is cut; ties
// go to fewer cuts in z, then in y (particles fall along z: fewer migrations). Throws
// upgrain::Error naming the sizes when no factorisation fits.
// `unsplit_axis` (>= 0): that axis keeps one block.
std::array<int, 3> choose_blocks(int ranks, const Box& box, double min_block, int unsplit_axis = -1);

class Decomposition {
 public:
  // blocks {0, 0, 0}: chosen by choose_blocks(). Collective over `comm`. Throws
  // upgrain::Error (on every rank) when px py pz differs from the rank count or a block is
  // thinner than `min_block` (the interaction range: largest diameter + skin), or when a
  // periodic axis is not longer than twice `min_block` (a grain would then meet two images of
  // another, and the minimum image would not be the only one in range).
  // `growth`: the periodic cell's position grid is sized for a cell that many times larger
  // (make_periodic_cell(); a cell that deforms, deform()).
  // `unsplit_axis`: an axis that must keep one block (a sheared cell's shear axis): chosen so,
  // or refused when `blocks` cut it.
  Decomposition(MPI_Comm comm, const Box& box, double min_block, std::array<int, 3> blocks = {0, 0, 0},
                std::array<bool, 3> periodic = {false, false, false}, double growth = 1.0,
                int unsplit_axis = -1);
  ~Decomposition();
  Decomposition(const Decomposition&) = delete;
  Decomposition& operator=(const Decomposition&) = delete;

  [[nodiscard]] MPI_Comm comm() const { return cart_; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  [[nodiscard]] const std::array<int, 3>& blocks() const { return dims_; }
  [[nodiscard]] const std::array<int, 3>& coords() const { return coords_; }
  [[nodiscard]] const Box& box() const { return box_; }
  // This rank's block; the open outer faces are +-infinity.
  [[nodiscard]] const Box& block() const { return block_; }
  // Neighbour rank across the lower (side 0) or upper (side 1) face along axis d, or
  // MPI_PROC_NULL at the border of the box along a bounded axis.
  [[nodiscard]] int neighbor(int d, int side) const { return neighbor_[d][side]; }
  // The box with the periodic flags: the cell.
  [[nodiscard]] const PeriodicCell& cell() const { return cell_; }
  [[nodiscard]] bool periodic(int d) const { return cell_.periodic[d]; }
  // The shift a position takes when it crosses face `side` of this block along axis d into the
  // neighbour: +L (side 0) or -L (side 1) across a face of a periodic cell, else 0.
  [[nodiscard]] double image_shift(int d, int side) const { return image_shift_[d][side]; }
  // The periodic cell moves to `cell_box` (its periodic faces on the grid); the planes follow
  // it, fixed in fractional coordinates, and the image shifts are the new lengths. Not
  // collective, but every rank passes the same. Throws upgrain::Error when a periodic axis
  // would not be longer than twice the interaction range, a block would be thinner than the
  // range (its ghosts would need a second neighbour), or the cell grows past what its position
  // grid holds (grid_holds()).
  void deform(const Box& cell_box);
  // A sheared cell's sliding images (periodic_cell.h): both axes periodic, the shear axis in one
  // block. Throws upgrain::Error otherwise. Not collective; every rank passes the same.
  void set_shear(const ShearImages& shear);
  // The step (-1, 0 or +1) from this block's coordinate towards block coordinate c along d: the
  // shorter way round along a periodic axis.
  [[nodiscard]] int step_towards(int d, int c) const;

  // Block coordinates of a point (clamped into the grid: the outer blocks are open).
  [[nodiscard]] std::array<int, 3> block_of(const Vec3& x) const;
  [[nodiscard]] int rank_of_block(const std::array<int, 3>& c) const;
  [[nodiscard]] int owner_of(const Vec3& x) const { return rank_of_block(block_of(x)); }
  // The k-th plane along axis d (k = 0 .. blocks[d]); block k spans planes k and k + 1.
  // Planes 0 and blocks[d] are the box faces.
  [[nodiscard]] double plane(int d, int k) const { return planes_[d][static_cast<std::size_t>(k)]; }
  [[nodiscard]] double min_block() const { return min_block_; }

  // Moves the blocks[d] - 1 interior planes along axis d to `cuts` (load balance). Not
  // collective, but every rank must pass the same cuts. Throws upgrain::Error unless they
  // ascend inside the box and every interior block (between two cuts) is at least
  // min_block() thick: the ghost layer of a face must not reach past the next face. The
  // outer blocks are open outwards and need no thickness (clamp_cuts, load_balance.h).
  void set_cuts(int d, const std::vector<double>& cuts);

 private:
  MPI_Comm cart_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  std::array<int, 3> dims_{1, 1, 1};
  std::array<int, 3> coords_{0, 0, 0};
  std::array<std::array<int, 2>, 3> neighbor_{};
  std::array<std::array<double, 2>, 3> image_shift_{};
  Box box_, block_;
  PeriodicCell cell_;
  double min_block_ = 0.0;
  std::array<std::vector<double>, 3> planes_;  // blocks[d] + 1 per axis
  void update_block();
};

}  // namespace upgrain::dem
