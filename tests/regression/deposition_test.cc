// Deposition of about 1,000 spheres into an open box: every grain ends inside the
// container, the bed comes to rest, energy is accounted for, and the packing is that of a
// random frictional packing.
#include <gtest/gtest.h>

#include "coupling/run/scene_run.h"
#include "dem/time_step.h"

using namespace upgrain::dem;
using upgrain::coupling::run_scene;
using upgrain::coupling::RunControl;
using upgrain::coupling::RunResult;

namespace {
SceneConfig deposition_scene() {
  SceneConfig s;
  s.particles.count = 1000;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = 0.03;
  s.fill.bottom_gap = 0.01;
  s.fill.position_jitter = 0.5;
  s.friction = 0.5;
  s.damping_ratio = 0.7;
  s.time_step = 1e-5;
  s.end_time = 2.0;  // an upper bound: the run stops once at rest (rest_ratio below)
  return s;
}
}  // namespace

TEST(Deposition, ThousandSpheresSettleIntoAStableBed) {
  const SceneConfig s = deposition_scene();
  ASSERT_LE(s.time_step, estimate_time_step(s).safe_step);
  RunControl control;
  control.rest_ratio = 1e-7;
  const RunResult r = run_scene(s, control, std::nullopt);
  std::printf(
      "steps %ld, KE/released %.3e, balance error %.3e, solid fraction %.4f, surface %.4f m, "
      "contacts/particle %.2f, %.3g particle-steps/s\n",
      r.steps, r.kinetic_to_released, r.energy_balance_error, r.bed.solid_fraction, r.bed.surface_height,
      2.0 * r.diagnostics.particle_contacts / 1000.0, r.particle_steps_per_second);
  EXPECT_EQ(r.bed.particles_outside, 0);
  EXPECT_LT(r.kinetic_to_released, 1e-6);
  EXPECT_LT(std::abs(r.energy_balance_error), 0.01);
  EXPECT_GT(r.bed.solid_fraction, 0.55);
  EXPECT_LT(r.bed.solid_fraction, 0.66);
  EXPECT_GT(r.energy.dissipated_friction, 0.0);
  EXPECT_GT(r.energy.dissipated_damping, 0.0);
}
