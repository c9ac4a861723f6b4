// Beds that stress the engine: a wide size ratio (1:10 spheres, 1:5 ellipsoids), extreme-aspect
// grains (10:1 needles and 10:1 discs), and a relaxed bed held at rest for long. Each reaches
// rest with nothing lost, no energy gain and no contact-solver failure, then holds still.
// Reduced sizes here; bench/hard_cases.sh runs the full ones (docs/hard-cases.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "../common/relaxed_bed.h"
#include "coupling/run/scene_run.h"
#include "dem/scene/fill.h"
#include "dem/time_step.h"
#include "full_size.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

struct BedRun {
  coupling::RunResult r;
  double safe_step = 0.0;
  // The neighbour search's own cost: the whole rebuilds (binning, sorting, the Verlet lists;
  // no migration on one rank) against the force evaluations over the lists, from the
  // engine's timers (StepTimings), as shares of the step loop's time.
  double rebuild_share = 0.0, force_share = 0.0;
  // Pairs in the Verlet lists per touching pair at the end: the force loop's candidates, which
  // the cells and the skin sized by the largest grain multiply for the small ones.
  double pairs_per_contact = 0.0;
  std::unique_ptr<Simulation> sim;  // the bed at the end
};

// Deposits at 0.9 of the safe step until rest (kinetic / released < 1e-6) or `end_time`.
BedRun deposit(SceneConfig s, double end_time = 2.0) {
  BedRun b;
  b.safe_step = estimate_time_step(s).safe_step;
  s.time_step = 0.9 * b.safe_step;
  s.end_time = end_time;
  coupling::RunControl control;
  control.rest_ratio = 1e-6;
  b.sim = std::make_unique<Simulation>(s, fill_container(s));
  Simulation& sim = *b.sim;
  b.r = coupling::run_scene(sim, control, std::nullopt);
  const StepTimings& t = sim.timings();
  b.rebuild_share = t.rebuild / t.total();
  b.force_share = t.forces / t.total();
  b.pairs_per_contact = static_cast<double>(sim.rank_diagnostics().pair_slots) /
                        static_cast<double>(std::max(1L, b.r.diagnostics.particle_contacts));
  const ContactSolverStats& st = b.r.diagnostics.contact_solver;
  std::printf(
      "%ld grains: dt %.3g s, %ld steps, at rest %d (KE/released %.1e), balance %.2e, max overlap %.4f of "
      "the "
      "smallest semi-axis, outside %ld, solver calls %ld failures %ld uncertified %ld, %.3g "
      "particle-steps/s, "
      "%ld neighbour builds; translational KE/released %.1e, rotational share of the kinetic energy %.3f; "
      "time in neighbour-list rebuilds %.2f %%, in force evaluations %.1f %%; %.1f list pairs per contact\n",
      s.particles.count, s.time_step, b.r.steps, b.r.stopped_at_rest, b.r.kinetic_to_released,
      b.r.energy_balance_error, b.r.diagnostics.max_overlap_ratio, b.r.bed.particles_outside,
      static_cast<long>(st.calls), static_cast<long>(st.failures), static_cast<long>(st.uncertified),
      b.r.particle_steps_per_second, b.r.diagnostics.neighbor_builds,
      b.r.energy.kinetic_translational / b.r.potential_released,
      b.r.energy.kinetic_rotational / b.r.energy.kinetic(), 100 * b.rebuild_share, 100 * b.force_share,
      b.pairs_per_contact);
  return b;
}

// At rest: the translational kinetic energy below 1e-6 of the potential energy released.
// Rotation is left out: without twisting resistance a grain spinning about its contact normal
// meets no torque (docs/contact-law.md), and a bed kept such spinners while its grains stayed in
// place; the beds here switch it on, but the invariant stays the one that holds without it.
void expect_sound_bed(const BedRun& b, double overlap_limit) {
  EXPECT_LT(b.r.energy.kinetic_translational / b.r.potential_released, 1e-6);
  EXPECT_EQ(b.r.bed.particles_outside, 0);
  EXPECT_LT(b.r.energy_balance_error, 0.01) << "no energy gain beyond the usual band";
  EXPECT_GT(b.r.energy_balance_error, -0.01);
  EXPECT_LT(b.r.diagnostics.max_overlap_ratio, overlap_limit);
  EXPECT_EQ(b.r.diagnostics.contact_solver.failures, 0);
  EXPECT_EQ(b.r.diagnostics.contact_solver.uncertified, 0);
}

// The bed at rest held by the plain dynamics for `steps` (damping on, as deposited), in two
// halves: a bed that creeps keeps moving in the second half as in the first. Largest centre
// displacement of each half over the smallest semi-axis c, and the kinetic energy over the
// potential energy released, largest at the ends of 20 chunks. `movers`: the grains that moved
// by more than 1e-2 c in the second half; `second_half_rest` the largest displacement of the
// others.
struct Hold {
  double first_half = 0.0, second_half = 0.0, kinetic_max = 0.0;
  long movers = 0;
  double second_half_rest = 0.0;
};

Hold hold_at_rest(Simulation& sim, long steps, double c) {
  const double released = sim.initial_energy().potential - sim.energy().potential;
  Hold h;
  ParticleStore from = sim.gather_sorted_by_id();
  for (double* half : {&h.first_half, &h.second_half}) {
    for (int k = 0; k < 10; ++k) {
      sim.run(steps / 20);
      h.kinetic_max = std::max(h.kinetic_max, sim.energy().kinetic() / released);
    }
    const ParticleStore to = sim.gather_sorted_by_id();
    for (std::size_t i = 0; i < to.size(); ++i) {
      const double d = (to.x[i] - from.x[i]).norm() / c;
      *half = std::max(*half, d);
      if (half != &h.second_half) continue;
      if (d <= 1e-2) {
        h.second_half_rest = std::max(h.second_half_rest, d);
        continue;
      }
      ++h.movers;
      std::printf(
          "  moving in the second half: grain %ld by %.2e c at height %.4f m, speed %.2e m/s, spin "
          "(%.2e, %.2e, %.2e) rad/s\n",
          static_cast<long>(to.id[i]), d, to.x[i].z(), to.v[i].norm(), to.omega[i].x(), to.omega[i].y(),
          to.omega[i].z());
    }
    from = to;
  }
  std::printf(
      "held %ld steps: largest displacement %.2e c in the first half, %.2e c in the second (%ld grains above "
      "1e-2 c, the others at most %.2e c); KE/released at most %.2e\n",
      steps, h.first_half, h.second_half, h.movers, h.second_half_rest, h.kinetic_max);
  return h;
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
  // Without twisting resistance a grain spinning about a contact normal meets no torque: a
  // needle lying on the floor kept turning (0.55 rad/s) and moved its centre by 2e-2 c per
  // 5e4 steps of a hold. With it (Hertz–Mindlin torsion), the spin stops.
  s.effects.twisting_resistance = true;
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

TEST(HardBeds, WideSizeRatioOneToFiveEllipsoidsReachRestWithTheStepOfTheSmallestGrain) {
  // 1:0.8:0.6 ellipsoids with major semi-axes 0.6-3 mm by mass.
  SceneConfig s = bed_scene(test::hard_size(60, 1000), 3e-3, test::hard_full_size() ? 0.04 : 0.018);
  s.particles.gradation = {{0.6e-3, 0.0}, {3e-3, 1.0}};
  s.particles.shapes = {ellipsoid_grain(0.8, 0.6, 1.0)};
  s.fill.method = FillMethod::random;
  SceneConfig smallest = s;
  smallest.particles.gradation.clear();
  smallest.particles.radius = 0.6e-3;
  const BedRun b = deposit(s, 1.0);
  EXPECT_NEAR(b.safe_step, estimate_time_step(smallest).safe_step, 1e-12 * b.safe_step);
  expect_sound_bed(b, 0.05);
}

TEST(HardBeds, NeedlesTenToOneReachRest) {
  SceneConfig s = bed_scene(test::hard_size(25, 300), 3e-3, test::hard_full_size() ? 0.04 : 0.018);
  s.particles.shapes = {ellipsoid_grain(0.1, 0.1, 1.0)};
  const BedRun b = deposit(s);
  expect_sound_bed(b, 0.05);
  // Held 1e5 steps: it stays at rest by the deposition's own criterion and no needle creeps.
  // Without twisting resistance a needle lying on the floor kept spinning about the floor's
  // normal and moved by 2e-2 c in each half (docs/hard-cases.md).
  const Hold h = hold_at_rest(*b.sim, 100000, 0.1 * s.particles.radius);
  EXPECT_LT(h.kinetic_max, 1e-6);
  EXPECT_LT(h.second_half, 1e-2);
  EXPECT_LE(h.second_half, 1.1 * h.first_half);
}

TEST(HardBeds, DiscsTenToOneReachRest) {
  SceneConfig s = bed_scene(test::hard_size(25, 300), 3e-3, test::hard_full_size() ? 0.04 : 0.018);
  s.particles.shapes = {ellipsoid_grain(1.0, 0.1, 1.0)};
  const BedRun b = deposit(s);
  expect_sound_bed(b, 0.05);
  // Held 1e5 steps: it stays at rest by the deposition's own criterion and the bed does not
  // creep. One disc in a hundred may still move: at full size a disc standing near upright on
  // its rim on top of the bed rolls round it, its spin about the vertical rising (1.4 to
  // 3.7 rad/s) as it leans over, as Euler's disk does (Moffatt 2000, Nature 404:833). A rim has
  // a radius of curvature of c^2/a, so neither the rolling nor the twisting resistance, both
  // proportional to the contact's size, can hold it; that is the physics of a thin disc
  // (docs/hard-cases.md).
  const Hold h = hold_at_rest(*b.sim, 100000, 0.1 * s.particles.radius);
  EXPECT_LT(h.kinetic_max, 1e-6);
  EXPECT_LE(h.movers, s.particles.count / 100);
  EXPECT_LT(h.second_half_rest, 1e-2);
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
