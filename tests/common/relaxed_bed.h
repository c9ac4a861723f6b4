#pragma once
// A bed of monodisperse spheres of Yan and Regueiro's size (docs/stress.md) (r = 1.5 mm) deposited into a
// square box about as wide as the bed is high, then relaxed to static equilibrium by FIRE
// (dem/engine/relaxation.h). The soft grains (E = 5e7 Pa) keep the run short; the stress
// symmetry at rest does not depend on the stiffness.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "dem/engine/relaxation.h"
#include "dem/scene/fill.h"
#include "dem/stress/grid_stress.h"
#include "dem/time_step.h"

namespace upgrain::test {

inline dem::SceneConfig paper_bed_scene(long count) {
  dem::SceneConfig s;
  s.particles.count = count;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  const double grain = 4.0 / 3.0 * std::numbers::pi * std::pow(1.5e-3, 3);
  s.container.lx = s.container.ly = std::max(std::cbrt(count * grain / 0.6), 0.012);
  s.fill.bottom_gap = 0.002;
  s.fill.position_jitter = 0.5;
  s.friction = 0.5;
  s.damping_ratio = 0.7;
  s.time_step = 1e-5;
  return s;
}

// Yan and Regueiro's ellipsoid beds (Table 3): the four shapes 1:1:1, 1:0.8:0.6, 1:0.8:0.4,
// 1:0.6:0.4 in equal numbers, major semi-axes 1.0-2.5 mm, random orientations, the soft
// material of paper_bed_scene, in a square box at least 2 cm wide and about as wide as the
// bed is high, at 0.9 of the safe time step.
inline dem::SceneConfig paper_ellipsoid_bed_scene(long count) {
  dem::SceneConfig s = paper_bed_scene(count);
  s.particles.gradation = {{1.0e-3, 0.0}, {2.5e-3, 1.0}};
  s.particles.shapes = {dem::ellipsoid_grain(1.0, 1.0, 1.0), dem::ellipsoid_grain(0.8, 0.6, 1.0),
                        dem::ellipsoid_grain(0.8, 0.4, 1.0), dem::ellipsoid_grain(0.6, 0.4, 1.0)};
  // Mean grain volume: a of about 1.75 mm, the shapes' mean b c / a^2 of 0.51.
  const double grain = 4.0 / 3.0 * std::numbers::pi * std::pow(1.75e-3, 3) * 0.51;
  s.container.lx = s.container.ly = std::max(std::cbrt(count * grain / 0.6), 0.02);
  s.time_step = 0.9 * dem::estimate_time_step(s).safe_step;
  return s;
}

struct RelaxedBed {
  std::unique_ptr<dem::Simulation> sim;
  dem::RelaxationResult settled;  // residuals when the deposition stopped
  dem::RelaxationResult relaxation;
  double total_energy_before = 0.0;  // J, when the relaxation started
  double total_energy_after = 0.0;
};

// Deposits until the kinetic energy is below `rest_ratio` of the potential energy
// released, then relaxes (when relax is true).
// `max_steps` bounds the FIRE steps: a budget, not a tolerance (the residual must still reach
// `tolerance`).
inline RelaxedBed relaxed_bed(const dem::SceneConfig& s, double rest_ratio = 1e-4, bool relax = true,
                              double tolerance = 1e-9, long max_steps = dem::RelaxationOptions{}.max_steps) {
  RelaxedBed b;
  b.sim = std::make_unique<dem::Simulation>(s, dem::fill_container(s));
  const long chunk = 2000, limit = 2000000;
  for (long steps = 0; steps < limit; steps += chunk) {
    b.sim->run(chunk);
    if (steps > 10 * chunk && b.sim->kinetic_to_released() < rest_ratio) break;
  }
  b.settled = dem::equilibrium_residual(*b.sim);
  if (relax) {
    dem::RelaxationOptions o;
    o.force_tolerance = tolerance;
    o.max_steps = max_steps;
    b.total_energy_before = b.sim->energy().total();
    b.relaxation = dem::relax_to_equilibrium(*b.sim, o);
    b.total_energy_after = b.sim->energy().total();
  }
  return b;
}

// One step with the contacts recorded, then the stress over `cells` of the box from the
// floor to the top of the highest grain.
inline dem::GridStress bed_stress(dem::Simulation& sim, const int cells[3],
                                  dem::RegularGrid* grid_out = nullptr) {
  sim.request_contacts();
  sim.step();
  const dem::ParticleStore& p = sim.particles();
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  dem::RegularGrid grid;
  grid.hi = dem::Vec3(sim.scene().container.lx, sim.scene().container.ly, top);
  for (int d = 0; d < 3; ++d) grid.n[d] = cells[d];
  if (grid_out) *grid_out = grid;
  return dem::grid_stress(p, sim.contacts(), grid, {sim.gravity(), sim.integrates_rotation()});
}

}  // namespace upgrain::test
