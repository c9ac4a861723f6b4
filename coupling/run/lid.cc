#include "coupling/run/lid.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "dem/core/error.h"
#include "dem/core/material.h"

namespace upgrain::coupling {

long Lid::index(const dem::Simulation& sim) {
  const auto& walls = sim.walls();
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (walls[w].name == kLidWallName) return static_cast<long>(w);
  return -1;
}

double Lid::stress(const dem::Simulation& sim) {
  const long w = index(sim);
  const std::vector<dem::Vec3> forces = sim.wall_forces();
  if (w < 0) return 0.0;
  const dem::PlaneWall& lid = sim.walls()[static_cast<std::size_t>(w)];
  const double area = sim.scene().container.lx * sim.scene().container.ly;
  return -forces[static_cast<std::size_t>(w)].dot(lid.normal) / area + 0.0;  // + 0.0: no -0
}

void Lid::place(dem::Simulation& sim) {
  // The highest grain top (a bounding sphere's for ellipsoids) over every rank.
  const dem::ParticleStore& p = sim.particles();
  double top = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < sim.owned(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  MPI_Allreduce(MPI_IN_PLACE, &top, 1, MPI_DOUBLE, MPI_MAX, sim.comm());
  if (!std::isfinite(top)) throw Error("Lid: no grain to place the lid on");
  dem::PlaneWall lid{kLidWallName, dem::Vec3(0.0, 0.0, top + control_.gap), dem::Vec3(0.0, 0.0, -1.0),
                     control_.friction};
  sim.add_wall(lid);
  if (control_.mode == LidControl::Mode::velocity)
    sim.set_wall_velocity(sim.wall_index(kLidWallName), dem::Vec3(0.0, 0.0, -control_.speed));
}

void Lid::before_step(dem::Simulation& sim) {
  if (!control_.enabled() || sim.time() < control_.place_time) return;
  long w = index(sim);
  if (w < 0) {
    place(sim);
    w = index(sim);
  }
  if (control_.mode != LidControl::Mode::servo || sim.step_count() % control_.update_every != 0) return;
  // The grains that may touch the lid (their bounding spheres cross it) and, once, the largest
  // Hertz radius a wall can see (a^2 / c of an ellipsoid: its flattest curvature), over every
  // rank: the stiffness bound's N and r_max.
  const dem::ParticleStore& p = sim.particles();
  const dem::PlaneWall& lid = sim.walls()[static_cast<std::size_t>(w)];
  double local[2] = {0.0, 0.0};
  for (int i = 0; i < sim.owned(); ++i) {
    if (lid.distance(p.x[i]) < p.radius[i]) local[0] += 1.0;
    if (r_max_ == 0.0)
      local[1] = std::max(local[1], p.radius[i] * p.radius[i] / p.min_semi_axis(static_cast<std::size_t>(i)));
  }
  double global[2] = {0.0, 0.0};
  MPI_Allreduce(&local[0], &global[0], 1, MPI_DOUBLE, MPI_SUM, sim.comm());
  if (r_max_ == 0.0) {
    MPI_Allreduce(&local[1], &global[1], 1, MPI_DOUBLE, MPI_MAX, sim.comm());
    r_max_ = global[1];
  }
  const dem::SceneConfig& scene = sim.scene();
  const double area = scene.container.lx * scene.container.ly;
  const double stress_now = stress(sim);
  const dem::ServoSettings servo{control_.target_at(sim.time()), area, control_.gain_factor,
                                 control_.max_speed};
  const double e_star = dem::effective_youngs_modulus(scene.particles.material, scene.particles.material);
  const double k =
      dem::hertz_wall_stiffness_bound(std::max(stress_now, 0.0) * area, global[0], e_star, r_max_);
  const double dt = static_cast<double>(control_.update_every) * sim.time_step();
  const double speed = dem::servo_speed(servo, stress_now, k, dt);
  sim.set_wall_velocity(static_cast<std::size_t>(w), dem::Vec3(0.0, 0.0, -speed));
}

}  // namespace upgrain::coupling
