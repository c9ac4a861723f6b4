#include "coupling/femxdem/rve_preparation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "coupling/femxdem/held_cell.h"
#include "coupling/femxdem/rve_tangent.h"
#include "coupling/studies/element/element_cell.h"
#include "dem/core/error.h"
#include "dem/engine/unbalanced_force.h"
#include "dem/scene/fill.h"

namespace upgrain::coupling {

namespace {

// The servo's progress is looked at every this many steps.
constexpr long kServoCheckEvery = 100;

// The scene's grains in a fully periodic cube, no gravity, no walls, no pour, squeezed by a servo to p0 on
// every axis. The random fill keeps each grain a radius from the box's faces (dem/scene/fill.cc), so
// the cube is sized for the fill's solid fraction over the region the centres may take,
// solids / (L - 2 r_max)^3: for a few dozen equal grains the whole cube at that fraction leaves
// the centres too little room to be placed at all.
dem::SceneConfig cell_scene(dem::SceneConfig scene, const RveOptions& o) {
  scene.particles.count = o.grains;
  scene.particles.packing = nullptr;
  scene.insertion = {};
  scene.effects.gravity = false;
  // No walls, and nothing reads a cell's energy: the force loop without the wall-friction and
  // energy-tracking work per contact (docs/femxdem.md, "Cost").
  scene.effects.wall_friction = false;
  scene.effects.energy_tracking = false;
  scene.fill.method = dem::FillMethod::random;
  scene.fill.bottom_gap = 0.0;
  scene.fill.velocity = dem::Vec3::Zero();
  scene.fill.velocity_jitter = 0.0;
  scene.fill.seed = o.seed;
  if (o.preparation_friction >= 0.0) scene.friction = o.preparation_friction;
  double solids = 0.0, r_max = 0.0;
  for (double r : dem::plan_fill(scene).radii) {
    solids += 4.0 / 3.0 * std::numbers::pi * r * r * r;
    r_max = std::max(r_max, r);
  }
  const double side = std::cbrt(solids / o.fill_solid_fraction) + 2.0 * r_max;
  scene.fill.solid_fraction = solids / (side * side * side);  // the fill's height is then the side
  scene.container.lx = scene.container.ly = scene.container.height = side;
  scene.container.periodic = {true, true, true};
  scene.cell = every_axis(cell_servo(o.mean_stress, o.servo_gain, o.max_strain_rate));
  return scene;
}

bool at_pressure(const dem::Simulation& sim, const RveOptions& o) {
  for (int d = 0; d < 3; ++d)
    if (std::abs(-sim.cell_stress()(d, d) - o.mean_stress) > o.servo_tolerance * o.mean_stress) return false;
  return true;
}

// The template's frame from the still cell: the scene its state is continued under (with the
// scene's own friction back), the engine's options and the grains.
RveTemplate frame_of(const dem::Simulation& sim, const dem::SceneConfig& scene_in) {
  RveTemplate t;
  t.scene = sim.scene();
  t.scene.friction = scene_in.friction;
  t.engine = sim.options();
  t.grains = sim.particle_count();
  for (int i = 0; i < sim.owned(); ++i)
    t.grain_volume += 4.0 / 3.0 * std::numbers::pi * std::pow(sim.particles().radius[i], 3);
  return t;
}

}  // namespace

RveTemplate rve_frame(const dem::SceneConfig& scene_in, const RveOptions& o) {
  if (o.grains < 2) throw Error("the DEM cell: at least 2 grains");
  const dem::SceneConfig scene = cell_scene(scene_in, o);
  ElementCell cell(scene, dem::fill_container(scene), MPI_COMM_SELF, {}, {});
  cell.control(still_cell());
  return frame_of(cell.sim(), scene_in);
}

RveTemplate prepare_rve(const dem::SceneConfig& scene_in, const RveOptions& o) {
  if (o.grains < 2) throw Error("the DEM cell: at least 2 grains");
  dem::SceneConfig scene = cell_scene(scene_in, o);
  ElementCell cell(scene, dem::fill_container(scene), MPI_COMM_SELF, {}, {});
  long steps = 0;
  while (!(at_pressure(cell.sim(), o) &&
           dem::unbalanced_force_ratio(cell.sim()) <= o.unbalanced_force_tolerance)) {
    if (steps >= o.preparation_step_cap)
      throw Error("the DEM cell's preparation: the servo did not bring every axis within " +
                  std::to_string(o.servo_tolerance) + " of p0 = " + std::to_string(o.mean_stress) +
                  " Pa at an unbalanced-force ratio of " + std::to_string(o.unbalanced_force_tolerance) +
                  " in " + std::to_string(o.preparation_step_cap) + " steps");
    cell.sim().run(kServoCheckEvery);
    steps += kServoCheckEvery;
  }
  cell.control(still_cell());
  const HeldCellRelaxation r =
      relax_held_cell(cell.sim(), o.relaxation, o.unbalanced_force_tolerance, o.preparation_step_cap - steps);
  steps += r.steps;
  if (!r.converged)
    throw Error("the DEM cell's preparation: the held cell did not relax to an unbalanced-force ratio of " +
                std::to_string(o.unbalanced_force_tolerance) + " (" + std::to_string(r.unbalanced_force) +
                ")");
  dem::Simulation& sim = cell.sim();
  RveTemplate t = frame_of(sim, scene_in);
  t.steps = steps;
  t.state = sim.capture_state();
  t.reference_cell = sim.cell_matrix();
  const dem::Mat3 sigma = sim.cell_stress();
  t.stress = fem::mandel::from_matrix(0.5 * (sigma + sigma.transpose()));
  t.elastic_tangent = contact_tangent(sim, dem::Mat3::Identity());
  t.contacts = sim.diagnostics().particle_contacts;
  t.unbalanced_force = r.unbalanced_force;
  return t;
}

}  // namespace upgrain::coupling
