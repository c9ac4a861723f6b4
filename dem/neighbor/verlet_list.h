#pragma once
// Verlet neighbour list with a skin (Verlet 1967; Allen and Tildesley 2017, sec. 5.3):
// a half list of pairs closer than r_i + r_j + skin, rebuilt from link cells when the
// largest displacement since the last build exceeds half the skin.
//
// The list also carries each pair's tangential spring. Between rebuilds the spring is
// addressed by the pair's slot (no lookups per contact); at a rebuild the springs of
// active contacts are carried over by the pair of global ids, so history survives
// reordering and, later, migration between ranks.
#include <vector>

#include "dem/contact/contact_response.h"
#include "dem/contact/rolling_resistance.h"
#include "dem/core/particle_store.h"
#include "dem/core/types.h"
#include "dem/neighbor/cell_grid.h"

namespace upgrain::dem {

class VerletList {
 public:
  // The link cells span the particles' bounding box at each rebuild, so their memory is
  // proportional to the particle count whatever the domain.
  VerletList(double max_radius, double skin, bool with_history);

  // True when some particle moved more than skin/2 since the last build.
  [[nodiscard]] bool needs_rebuild(const ParticleStore& p) const;

  // Sorts the particles by cell (for memory locality), then rebuilds the pair list and
  // carries the springs over. Reorders `p`.
  void rebuild(ParticleStore& p);

  // Positions at the last build and the squared displacement that triggers a rebuild,
  // for callers that check displacements inside a loop of their own.
  [[nodiscard]] const std::vector<Vec3>& positions_at_build() const { return x_at_build_; }
  [[nodiscard]] double rebuild_displacement2() const { return 0.25 * skin_ * skin_; }

  [[nodiscard]] const std::vector<int>& offsets() const { return offsets_; }
  [[nodiscard]] const std::vector<int>& partners() const { return partners_; }
  [[nodiscard]] std::vector<TangentialSpring>& springs() { return springs_; }
  [[nodiscard]] const std::vector<TangentialSpring>& springs() const { return springs_; }
  // Ellipsoid scenes: each slot also keeps its pair's contact memory (contact/contact_response.h:
  // the warm-start normal and the Hertz radius frozen at first touch); carried over rebuilds
  // like the springs.
  void keep_contact_memory() { with_memory_ = true; }
  [[nodiscard]] std::vector<ShapedContactMemory>& contact_memory() { return memory_; }
  // Scenes with rolling resistance: each slot also keeps its pair's rolling spring (torque on
  // i), carried over rebuilds like the springs.
  void keep_rolling_springs() { with_rolling_ = true; }
  [[nodiscard]] std::vector<RollingSpring>& rolling_springs() { return rolling_; }
  [[nodiscard]] long builds() const { return builds_; }
  [[nodiscard]] double skin() const { return skin_; }
  [[nodiscard]] std::size_t num_pairs() const { return partners_.size(); }

 private:
  CellGrid grid_;
  double cell_size_;
  double skin_;
  bool with_history_;
  bool with_memory_ = false;
  bool with_rolling_ = false;
  long builds_ = 0;
  std::vector<int> offsets_;                 // CSR: pairs of i are partners_[offsets_[i] .. offsets_[i+1])
  std::vector<int> partners_;                // j > i in the current local order
  std::vector<TangentialSpring> springs_;    // tangential spring per pair slot
  std::vector<ShapedContactMemory> memory_;  // per pair slot, normal from i to j
  std::vector<RollingSpring> rolling_;       // per pair slot, torque on i (rolling resistance)
  std::vector<Vec3> x_at_build_;
};

}  // namespace upgrain::dem
