#include "coupling/run/servo_walls.h"

#include <mpi.h>

#include <algorithm>

#include "dem/core/material.h"

namespace upgrain::coupling {

double wall_normal_stress(const dem::PlaneWall& wall, const dem::Vec3& force, double area) {
  return -force.dot(wall.normal) / area + 0.0;  // + 0.0: no -0
}

void ServoWalls::update(dem::Simulation& sim, const std::vector<ServoWall>& walls) {
  if (walls.empty() || sim.step_count() % update_every_ != 0) return;
  // Per wall, the grains that may touch it (their bounding spheres cross it), and, once, the
  // largest Hertz radius a wall can see (a^2 / c of an ellipsoid: its flattest curvature), over
  // every rank: the stiffness bound's N and r_max.
  const dem::ParticleStore& p = sim.particles();
  const std::size_t n = walls.size();
  std::vector<double> local(n + 1, 0.0), global(n + 1, 0.0);
  for (int i = 0; i < sim.owned(); ++i) {
    for (std::size_t w = 0; w < n; ++w)
      if (sim.walls()[walls[w].wall].distance(p.x[i]) < p.radius[i]) local[w] += 1.0;
    if (r_max_ == 0.0)
      local[n] = std::max(local[n], p.radius[i] * p.radius[i] / p.min_semi_axis(static_cast<std::size_t>(i)));
  }
  MPI_Allreduce(local.data(), global.data(), static_cast<int>(n), MPI_DOUBLE, MPI_SUM, sim.comm());
  if (r_max_ == 0.0) {
    MPI_Allreduce(&local[n], &global[n], 1, MPI_DOUBLE, MPI_MAX, sim.comm());
    r_max_ = global[n];
  }
  const std::vector<dem::Vec3> forces = sim.wall_forces();
  const dem::SceneConfig& scene = sim.scene();
  const double e_star = dem::effective_youngs_modulus(scene.particles.material, scene.particles.material);
  const double dt = static_cast<double>(update_every_) * sim.time_step();
  for (std::size_t w = 0; w < n; ++w) {
    const dem::PlaneWall& wall = sim.walls()[walls[w].wall];
    const double stress = wall_normal_stress(wall, forces[walls[w].wall], walls[w].area);
    const dem::ServoSettings servo{walls[w].target_stress, walls[w].area, gain_factor_, max_speed_};
    const double k =
        dem::hertz_wall_stiffness_bound(std::max(stress, 0.0) * walls[w].area, global[w], e_star, r_max_);
    if (integral_.size() < sim.walls().size()) integral_.resize(sim.walls().size(), 0.0);
    const double speed =
        dem::servo_speed_with_integral(servo, stress, k, dt, beta_, integral_[walls[w].wall]);
    // + 0: no -0 components in walls.csv
    sim.set_wall_velocity(walls[w].wall, speed * wall.normal + dem::Vec3::Zero());
  }
}

}  // namespace upgrain::coupling
