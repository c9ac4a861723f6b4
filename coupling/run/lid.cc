#include "coupling/run/lid.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "dem/core/error.h"

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
  const auto k = static_cast<std::size_t>(w);
  return wall_normal_stress(sim.walls()[k], forces[k], sim.scene().container.lx * sim.scene().container.ly);
}

double highest_grain_top(const dem::Simulation& sim) {
  const dem::ParticleStore& p = sim.particles();
  double top = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < sim.owned(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  MPI_Allreduce(MPI_IN_PLACE, &top, 1, MPI_DOUBLE, MPI_MAX, sim.comm());
  return top;
}

std::size_t place_lid(dem::Simulation& sim, double gap, double friction) {
  const double top = highest_grain_top(sim);
  if (!std::isfinite(top)) throw Error("Lid: no grain to place the lid on");
  sim.add_wall({kLidWallName, dem::Vec3(0.0, 0.0, top + gap), dem::Vec3(0.0, 0.0, -1.0), friction});
  return sim.wall_index(kLidWallName);
}

void Lid::before_step(dem::Simulation& sim) {
  if (!control_.enabled() || sim.time() < control_.place_time) return;
  long w = index(sim);
  if (w < 0) {
    w = static_cast<long>(place_lid(sim, control_.gap, control_.friction));
    if (control_.mode == LidControl::Mode::velocity)
      sim.set_wall_velocity(static_cast<std::size_t>(w), dem::Vec3(0.0, 0.0, -control_.speed));
  }
  if (control_.mode != LidControl::Mode::servo) return;
  const dem::SceneConfig& scene = sim.scene();
  servo_.update(sim, {{static_cast<std::size_t>(w), control_.target_at(sim.time()),
                       scene.container.lx * scene.container.ly}});
}

}  // namespace upgrain::coupling
