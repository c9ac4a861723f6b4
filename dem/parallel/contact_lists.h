#pragma once
// The neighbour lists of one rank, built for a deterministic force sum (docs/parallel.md).
// The local store holds the owned particles first, then the ghosts.
//  - Pair slots: every pair closer than r_i + r_j + skin with at least one owned particle,
//    once, oriented canonically (lo = the lower global id), with its tangential spring
//    stored as the force on lo. Any rank holding the pair evaluates it to the same bits.
//  - Rows: for each owned particle, its slots sorted by the partner's global id, so forces
//    are summed in an order that does not depend on ranks or local indices.
//  - Wall contacts of owned particles, sorted by (particle, wall).
// Springs are carried over rebuilds and migration as SpringRecords keyed by global ids.
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/contact/contact_response.h"
#include "dem/core/particle_store.h"
#include "dem/neighbor/cell_grid.h"
#include "dem/parallel/records.h"

namespace upgrain::dem {

struct WallContact {
  int particle;  // owned local index
  int wall;
  TangentialSpring spring;
};

struct ContactLists {
  // Pair slots.
  std::vector<int> lo, hi;  // local indices, id[lo] < id[hi]
  std::vector<TangentialSpring> spring;
  // Per-evaluation results of each slot: force on lo (hi gets -force), the torques on lo
  // and hi, and whether the pair touched.
  std::vector<Vec3> force, torque_lo, torque_hi;
  std::vector<unsigned char> touching;
  // With energy tracking: the slot's elastic energies and the viscous part of its force on
  // lo (hi receives the opposite).
  std::vector<double> elastic_normal, elastic_tangential;
  std::vector<Vec3> damping_on_lo;
  std::vector<Vec3> damping_torque_lo, damping_torque_hi;  // its torques (ellipsoid scenes)
  // CSR rows of the owned particles: entry 2 k + s for slot k, s = 1 when the row's
  // particle is the slot's hi.
  std::vector<int> row_start, row;
  // Ellipsoid scenes (build with memory): per slot the contact memory, its normal from lo
  // to hi; per wall entry the Hertz radius held while touching. Empty for spheres.
  std::vector<ShapedContactMemory> memory;
  std::vector<double> wall_r_star;
  std::vector<WallContact> wall;
  // Per wall entry, per evaluation: the force on the particle (zero when not touching).
  std::vector<Vec3> wall_force_on_particle;

  // Rebuilds everything from the local store (n_owned owned particles, then ghosts).
  // `history` and `memory_history` must be sorted and free of duplicate keys; with
  // `memory_history` (ellipsoid scenes) the lists keep contact memory.
  void build(const ParticleStore& p, int n_owned, double max_radius, double skin,
             const std::vector<PlaneWall>& walls, const std::vector<SpringRecord>& history,
             const std::vector<MemoryRecord>* memory_history = nullptr);
  // Appends the springs of touching contacts (nonzero stiffness) to `out`.
  void collect_springs(const ParticleStore& p, std::vector<SpringRecord>& out) const;
  // Appends the non-empty contact memories (ellipsoid scenes) to `out`.
  void collect_memory(const ParticleStore& p, std::vector<MemoryRecord>& out) const;
  [[nodiscard]] std::size_t num_pairs() const { return lo.size(); }

 private:
  CellGrid grid_;
};

}  // namespace upgrain::dem
