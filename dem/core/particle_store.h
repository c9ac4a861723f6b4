#pragma once
// Particle state as structure-of-arrays indexed by local index, with a persistent global
// id that survives reordering (and, later, migration between ranks). DESIGN.md.
#include <cstddef>
#include <vector>

#include "dem/core/types.h"

namespace upgrain::dem {

struct ParticleStore {
  std::vector<GlobalId> id;
  std::vector<double> radius;
  std::vector<double> inv_mass;     // 1 / m: the mass itself is not stored (8 B per grain less)
  std::vector<double> inv_inertia;  // sphere: 1 / (2/5 m r^2)
  std::vector<Vec3> x;              // centroid position (m)
  std::vector<Vec3> v;              // velocity (m/s)
  std::vector<Vec3> omega;          // angular velocity (rad/s)
  std::vector<Vec3> force;          // contact force of the current step (N)
  std::vector<Vec3> torque;         // contact torque about the centroid (N m)

  [[nodiscard]] std::size_t size() const { return id.size(); }
  [[nodiscard]] double mass(std::size_t i) const { return 1.0 / inv_mass[i]; }

  void reserve(std::size_t n);
  void add_sphere(GlobalId gid, double r, double density, const Vec3& pos, const Vec3& vel,
                  const Vec3& ang_vel);
  // Applies new[k] = old[perm[k]] to every array.
  void permute(const std::vector<int>& perm);

  [[nodiscard]] double max_radius() const;
  [[nodiscard]] double min_radius() const;
};

}  // namespace upgrain::dem
