#include "coupling/femxdem/rve_preparation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "coupling/femxdem/held_cell.h"
#include "coupling/femxdem/rve_tangent.h"
#include "coupling/studies/element/element_cell.h"
#include "dem/core/error.h"
#include "dem/engine/unbalanced_force.h"
#include "dem/scene/fill.h"
#include "dem/scene/weight_overlap.h"

namespace upgrain::coupling {

namespace {

// The servo's progress is looked at every this many steps.
constexpr long kServoCheckEvery = 100;

// The servo L_dd = g (p_dd - p) / p corrects the pressure at the rate g M / p (M the packing's
// constrained modulus at p); the cell answers only after a stress wave has crossed it, in
// t_w = L sqrt(rho / M) (L its side, rho its grains' mass over its volume). A loop whose
// correction outpaces its delay, g (M / p) t_w > 1, overshoots and hunts instead of settling (a
// delayed proportional control). This is that number, estimated before the fill for a random
// packing of the scene's grains at p: the mean contact force 4 pi r^2 p / (Z phi) and its
// overlap by the law (dem/scene/weight_overlap.h) give the contact stiffness k_n = dF / d delta,
// and the effective medium of such contacts K = Z phi k_n / (12 pi r), M ~ 2K (Walton 1987,
// J. Mech. Phys. Solids 35, 213), with Z = 6 and phi = 0.6. For Hertz grains M grows as p^(1/3),
// so the number grows as p^(-5/6): a servo that follows a cell of 1e9 Pa grains at 1e5 Pa (0.2)
// hunts at the hundreds of pascals a bed carries under its own weight.
double servo_delay_number(const dem::SceneConfig& scene, const std::vector<double>& radii, double gain,
                          double p) {
  constexpr double kCoordination = 6.0, kSolidFraction = 0.6;
  double solids = 0.0, r_mean = 0.0;
  for (const double r : radii) {
    solids += 4.0 / 3.0 * std::numbers::pi * r * r * r;
    r_mean += r / static_cast<double>(radii.size());
  }
  const auto overlap = [&](double pressure) {
    return r_mean * dem::stress_overlap_ratio(scene, {pressure, kCoordination, kSolidFraction});
  };
  const double force = 4.0 * std::numbers::pi * r_mean * r_mean * p / (kCoordination * kSolidFraction);
  const double stiffness = 0.01 * force / (overlap(1.01 * p) - overlap(p));
  const double modulus =
      2.0 * kCoordination * kSolidFraction * stiffness / (12.0 * std::numbers::pi * r_mean);
  const double side = std::cbrt(solids / kSolidFraction);
  const double density = scene.particles.material.density * kSolidFraction;
  return gain * modulus / p * side * std::sqrt(density / modulus);
}

// How a servo brings a cell to p0 where the configured one would hunt there
// (servo_delay_number() above 1/2, stiff grains at a low pressure; docs/femxdem.md, "Preparing a
// cell at a low pressure"). A fill squeezed towards a low target never jams: the stress of a
// single collision between stiff grains already exceeds it, and the servo backs off. So the fill
// is jammed by the configured servo at `jamming`, the first of 2 p0, 4 p0, ... where that servo
// follows the cell, and then brought down to p0 by a servo whose gain makes the number 1/2 and
// whose rate is bounded by that gain: the pressure then changes by at most its own size in a few
// wave times, slowly enough that the packing unloads through equilibrium states instead of
// springing apart. The overlaps of stiff grains are a small fraction of a radius at either
// pressure, so the solid fraction hardly depends on which.
// Whether unloading leaves more contacts at the Coulomb limit than jamming at p0 would is open.
struct LowPressureServo {
  double jamming = 0.0;  // Pa; equal to p0 when the configured servo follows the cell at p0
  double gain = 0.0;     // 1/s, the settling servo's gain and rate bound
};

LowPressureServo low_pressure_servo(const dem::SceneConfig& scene, const std::vector<double>& radii,
                                    const RveOptions& o) {
  LowPressureServo s{o.mean_stress, o.servo_gain};
  const double number = servo_delay_number(scene, radii, o.servo_gain, o.mean_stress);
  if (number <= 0.5) return s;
  s.gain = o.servo_gain * 0.5 / number;
  while (servo_delay_number(scene, radii, o.servo_gain, s.jamming) > 0.5 && s.jamming < 1e12)
    s.jamming *= 2.0;
  return s;
}

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
  for (const double r : dem::plan_fill(scene).radii) {
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
  for (int i = 0; i < sim.owned(); ++i) {
    t.grain_volume += 4.0 / 3.0 * std::numbers::pi * std::pow(sim.particles().radius[i], 3);
    t.grain_mass += sim.particles().mass(static_cast<std::size_t>(i));
  }
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
  // The servo in checks of kServoCheckEvery steps until `reached`, or an error naming its `goal`.
  const auto servo_until = [&](const auto& reached, const std::string& goal) {
    while (!reached()) {
      if (steps >= o.preparation_step_cap)
        throw Error("the DEM cell's preparation: the servo did not " + goal + " in " +
                    std::to_string(o.preparation_step_cap) + " steps");
      cell.sim().run(kServoCheckEvery);
      steps += kServoCheckEvery;
    }
  };
  const LowPressureServo low = low_pressure_servo(scene, dem::plan_fill(scene).radii, o);
  if (low.jamming != o.mean_stress) {
    cell.control(every_axis(cell_servo(low.jamming, o.servo_gain, o.max_strain_rate)));
    servo_until(
        [&] { return -cell.sim().cell_stress().trace() / 3.0 >= (1.0 - o.servo_tolerance) * low.jamming; },
        "jam the cell at " + std::to_string(low.jamming) +
            " Pa (to come down to p0 = " + std::to_string(o.mean_stress) + " Pa from there)");
    cell.control(every_axis(cell_servo(o.mean_stress, low.gain, low.gain)));
  }
  servo_until(
      [&] {
        return at_pressure(cell.sim(), o) &&
               dem::unbalanced_force_ratio(cell.sim()) <= o.unbalanced_force_tolerance;
      },
      "bring every axis within " + std::to_string(o.servo_tolerance) +
          " of p0 = " + std::to_string(o.mean_stress) + " Pa at an unbalanced-force ratio of " +
          std::to_string(o.unbalanced_force_tolerance));
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
