#pragma once
// Verlet neighbour lists with a skin (Verlet 1967; Allen and Tildesley 2017, sec. 5.3) over
// one rank's local store, owned particles first, then ghosts: the pairs closer than
// r_i + r_j + skin with at least one owned particle, and the owned particles within r + skin
// of each wall, found through link cells. They are rebuilt when some particle has moved more
// than skin/2 since the last build. The histories of the contacts live in their own store
// (dem/core/contact_history.h); the lists hold indices only.
//
// Each force summation (docs/architecture.md) has its order of the slots:
//  - PairOrder::local (fast summation): one row per owned particle, in local order; a row
//    holds its owned partners of higher local index and the ghost partners it evaluates
//    (evaluates_across_ranks), by local index. Every pair is in the lists of exactly one rank.
//    Wall entries by wall, then particle.
//  - PairOrder::global_id (deterministic summation): every pair is oriented from its lower
//    global id; the rows are sorted by the global id of their first particle and each row by
//    its partners'. A scatter over the slots in this order adds each particle's contributions
//    in the order of its partners' global ids, whatever the decomposition: lower partners
//    (in their rows, which come first), then higher ones (its own row). A pair across two
//    ranks is in the lists of both. Wall entries by particle, then wall.
#include <vector>

#include "dem/core/pair_list.h"
#include "dem/core/particle_store.h"
#include "dem/core/plane_wall.h"
#include "dem/neighbor/cell_grid.h"

namespace upgrain::dem {

enum class PairOrder { local, global_id };

class VerletList {
 public:
  // Link cells of 2 max_radius + skin, spanning the local particles at each build.
  VerletList(double max_radius, double skin, PairOrder order);

  // The lists of the local store `p` (n_owned owned particles, then ghosts) against `walls`.
  void build(const ParticleStore& p, int n_owned, const std::vector<PlaneWall>& walls);

  [[nodiscard]] const PairList& pairs() const { return pairs_; }
  [[nodiscard]] const WallList& walls() const { return walls_; }
  // Positions of the owned particles at the last build, and the squared displacement that
  // calls for a new one (skin/2), for the step's drift loop.
  [[nodiscard]] const std::vector<Vec3>& positions_at_build() const { return x_at_build_; }
  [[nodiscard]] double rebuild_displacement2() const { return 0.25 * skin_ * skin_; }
  // True when some owned particle of `p` moved more than skin/2 since the last build.
  [[nodiscard]] bool needs_rebuild(const ParticleStore& p) const;
  // The pair slots each owned particle takes part in (the load balance's cost).
  [[nodiscard]] const std::vector<int>& slots_per_owned() const { return slots_per_owned_; }
  [[nodiscard]] PairOrder order() const { return order_; }
  [[nodiscard]] double cell_size() const { return cell_size_; }
  [[nodiscard]] double skin() const { return skin_; }
  [[nodiscard]] long builds() const { return builds_; }

 private:
  void build_local(const ParticleStore& p, int n_owned);
  void build_global_id(const ParticleStore& p, int n_owned);
  void build_walls(const ParticleStore& p, int n_owned, const std::vector<PlaneWall>& walls);

  double cell_size_;
  double skin_;
  PairOrder order_;
  long builds_ = 0;
  CellGrid grid_;
  PairList pairs_;
  WallList walls_;
  std::vector<Vec3> x_at_build_;
  std::vector<int> slots_per_owned_;
};

// Of a pair across two ranks, whether the owner of `mine` evaluates it (fast summation):
// exactly one of the two owners does, the same decision on both.
bool evaluates_across_ranks(GlobalId mine, GlobalId other);

// Sorts the particles of `p` by link cell of size `cell_size` over their bounding box, for
// memory locality (the lists fix the order of every sum, so nothing else depends on it).
void sort_by_cell(ParticleStore& p, double cell_size);

}  // namespace upgrain::dem
