// Beds that stress the engine: a wide size ratio (1:10 spheres, 1:5 ellipsoids), extreme-aspect
// grains (10:1 needles and 10:1 discs), and a relaxed bed held at rest for long. Each reaches
// rest with nothing lost, no energy gain and no contact-solver failure, then holds still.
// Reduced sizes here; bench/hard_cases.sh runs the full ones (docs/hard-cases.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "../common/relaxed_bed.h"
#include "coupling/run/scene_run.h"
#include "dem/time_step.h"
#include "full_size.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

struct BedRun {
  coupling::RunResult r;
  double safe_step = 0.0;
};

// Deposits at 0.9 of the safe step until rest (kinetic / released < 1e-6) or `end_time`.
BedRun deposit(SceneConfig s, double end_time = 2.0) {
  BedRun b;
  b.safe_step = estimate_time_step(s).safe_step;
  s.time_step = 0.9 * b.safe_step;
  s.end_time = end_time;
  coupling::RunControl control;
  control.rest_ratio = 1e-6;
  b.r = coupling::run_scene(s, control, std::nullopt);
  const ContactSolverStats& st = b.r.diagnostics.contact_solver;
  std::printf(
      "%ld grains: dt %.3g s, %ld steps, at rest %d (KE/released %.1e), balance %.2e, max overlap %.4f of "
      "the "
      "smallest semi-axis, outside %ld, solver calls %ld failures %ld uncertified %ld, %.3g "
      "particle-steps/s, "
      "%ld neighbour builds; translational KE/released %.1e, rotational share of the kinetic energy %.3f\n",
      s.particles.count, s.time_step, b.r.steps, b.r.stopped_at_rest, b.r.kinetic_to_released,
      b.r.energy_balance_error, b.r.diagnostics.max_overlap_ratio, b.r.bed.particles_outside,
      static_cast<long>(st.calls), static_cast<long>(st.failures), static_cast<long>(st.uncertified),
      b.r.particle_steps_per_second, b.r.diagnostics.neighbor_builds,
      b.r.energy.kinetic_translational / b.r.potential_released,
      b.r.energy.kinetic_rotational / b.r.energy.kinetic());
  return b;
}

// At rest: the translational kinetic energy below 1e-6 of the potential energy released.
// Rotation is left out: a grain spinning about its contact normal meets no resistance (the law
// has no twisting torque, docs/contact-law.md), and the 1:10 bed keeps such spinners (all of
// its remaining kinetic energy is rotational) while its grains stay in place.
void expect_sound_bed(const BedRun& b, double overlap_limit) {
  EXPECT_LT(b.r.energy.kinetic_translational / b.r.potential_released, 1e-6);
  EXPECT_EQ(b.r.bed.particles_outside, 0);
  EXPECT_LT(b.r.energy_balance_error, 0.01) << "no energy gain beyond the usual band";
  EXPECT_GT(b.r.energy_balance_error, -0.01);
  EXPECT_LT(b.r.diagnostics.max_overlap_ratio, overlap_limit);
  EXPECT_EQ(b.r.diagnostics.contact_solver.failures, 0);
  EXPECT_EQ(b.r.diagnostics.contact_solver.uncertified, 0);
}

SceneConfig bed_scene(long count, double r_max, double width) {
  SceneConfig s;
  s.particles.count = count;
  s.particles.radius = r_max;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = width;
  s.fill.bottom_gap = 0.002;
  s.fill.position_jitter = 0.5;
  s.friction = 0.5;
  s.damping_ratio = 0.7;
  // Without rolling resistance a grain rolling on the free floor (a sphere, or a needle about
  // its long axis) keeps its energy: measured, 300 spheres of 1:10 and 40 needles still had
  // 5e-5 and 7e-5 of the released energy after 3 s. With it, they stop.
  s.effects.rolling_resistance = true;
  return s;
}

}  // namespace

TEST(HardBeds, WideSizeRatioOneToTenReachesRestWithTheStepOfTheSmallestGrain) {
  SceneConfig s = bed_scene(test::hard_size(120, 3000), 3e-3, test::hard_full_size() ? 0.05 : 0.018);
  s.particles.gradation = {{0.3e-3, 0.0}, {3e-3, 1.0}};  // radii 0.3-3 mm by mass
  s.fill.method = FillMethod::random;
  // The step is the smallest grain's: the Rayleigh time scales with r_min.
  SceneConfig smallest = s;
  smallest.particles.gradation.clear();
  smallest.particles.radius = 0.3e-3;
  const BedRun b = deposit(s, 1.0);  // its spinners keep it from stopping early
  EXPECT_NEAR(b.safe_step, estimate_time_step(smallest).safe_step, 1e-12 * b.safe_step);
  expect_sound_bed(b, 0.1);
}

TEST(HardBeds, NeedlesTenToOneReachRest) {
  SceneConfig s = bed_scene(test::hard_size(25, 300), 3e-3, test::hard_full_size() ? 0.04 : 0.018);
  s.particles.shapes = {{0.1, 0.1, 1.0}};
  expect_sound_bed(deposit(s), 0.05);
}

TEST(HardBeds, DiscsTenToOneReachRest) {
  SceneConfig s = bed_scene(test::hard_size(25, 300), 3e-3, test::hard_full_size() ? 0.04 : 0.018);
  s.particles.shapes = {{1.0, 0.1, 1.0}};
  expect_sound_bed(deposit(s), 0.05);
}

TEST(HardBeds, RelaxedBedHeldAtRestDoesNotCreep) {
  // A relaxed bed of spheres held by the plain dynamics: 1e6 steps of 1,000 spheres at full
  // size, 2e4 steps of 200 in CI. Its kinetic energy stays at the relaxation's level and no
  // grain moves by more than round-off.
  const long count = test::hard_size(200, 1000), steps = test::hard_size(20000, 1000000);
  test::RelaxedBed bed = test::relaxed_bed(test::paper_bed_scene(count));
  ASSERT_TRUE(bed.relaxation.converged);
  Simulation& sim = *bed.sim;
  const ParticleStore before = sim.gather_sorted_by_id();
  const double potential = sim.initial_energy().potential - sim.energy().potential;
  const double ke0 = sim.energy().kinetic() / potential;
  double ke_max = ke0;
  const long chunk = std::min(steps, 10000L);
  for (long k = 0; k < steps; k += chunk) {
    sim.run(chunk);
    ke_max = std::max(ke_max, sim.energy().kinetic() / potential);
  }
  const ParticleStore after = sim.gather_sorted_by_id();
  double drift = 0.0;
  for (std::size_t i = 0; i < after.size(); ++i)
    drift = std::max(drift, (after.x[i] - before.x[i]).norm() / after.radius[i]);
  std::printf(
      "%ld spheres held %ld steps: KE/released %.2e at the start, at most %.2e; largest drift %.2e r\n",
      count, steps, ke0, ke_max, drift);
  EXPECT_LT(ke_max, 1e-12);
  EXPECT_LT(drift, 1e-6);
}
