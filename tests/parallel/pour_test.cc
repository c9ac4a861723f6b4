// A pour (dem/engine/pour.h, docs/insertion.md) on K ranks gives the bits of the same pour on
// rank 0 alone: the grains inserted (ids, positions, shapes) and the run after them; the
// energy balance stays closed across the insertions, and no grain is lost.
#include <gtest/gtest.h>
#include <mpi.h>

#include "dem/engine/pour.h"
#include "dem/engine/simulation.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// 24 spheres lying on the floor, and 120 grains poured onto them from an inlet 3 cm up.
SceneConfig pour_scene(bool ellipsoids) {
  SceneConfig s = test::deposition_scene(24);
  s.container.lx = s.container.ly = 0.02;
  s.particles.radius = 1e-3;
  s.particles.gradation = {{0.7e-3, 0.0}, {1e-3, 1.0}};
  if (ellipsoids) s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(0.8, 0.6, 1.0)};
  s.fill.bottom_gap = 0.0005;
  s.fill.velocity = Vec3::Zero();
  s.fill.velocity_jitter = 0.0;
  s.insertion.count = 120;
  s.insertion.rate = 6000.0;
  s.insertion.interval = 0.002;
  s.insertion.inlet_lo = Vec3(0.001, 0.001, 0.02);
  s.insertion.inlet_hi = Vec3(0.019, 0.019, 0.03);
  s.insertion.velocity = Vec3(0.0, 0.0, -0.3);
  return s;
}

struct PourRun {
  ParticleStore state;
  PourState pour;
  double balance_error = 0.0;
};

PourRun pour_for(const SceneConfig& s, MPI_Comm comm, long steps) {
  Simulation sim(s, fill_container(s), comm);
  Pour pour(s);
  for (long k = 0; k < steps; ++k) {
    pour.before_step(sim);
    sim.step();
  }
  PourRun r;
  r.state = sim.whole_state();  // checked: no grain lost or doubled, the mass of the grains poured
  r.pour = pour.state();
  r.balance_error = sim.energy_balance_error();
  return r;
}

void expect_pour_rank_independent(bool ellipsoids) {
  const SceneConfig s = pour_scene(ellipsoids);
  // 0.04 s: every batch in (the last at 0.018 s), the first grains landed on the bed (after
  // about 0.03 s), the last still falling.
  const long steps = 4000;
  const PourRun world = pour_for(s, MPI_COMM_WORLD, steps);
  if (test::world_rank() != 0) return;
  EXPECT_EQ(world.pour.inserted, 120);
  EXPECT_EQ(world.state.size(), 144u);
  EXPECT_EQ(world.state.has_shapes(), ellipsoids);
  // Velocity Verlet with Hertz contacts: a drift of a fraction of a percent over impacts.
  EXPECT_LT(std::abs(world.balance_error), 0.01);
  const PourRun self = pour_for(s, MPI_COMM_SELF, steps);
  EXPECT_EQ(self.pour.inserted, world.pour.inserted);
  EXPECT_EQ(self.pour.batches, world.pour.batches);
  test::expect_bitwise_equal(world.state, self.state, std::to_string(test::world_size()) + " ranks vs 1");
  EXPECT_EQ(world.balance_error, self.balance_error);
}

}  // namespace

TEST(Pour, SpheresPouredOnAnyRankCountAreBitwiseIdentical) { expect_pour_rank_independent(false); }

TEST(Pour, EllipsoidsPouredOnAnyRankCountAreBitwiseIdentical) { expect_pour_rank_independent(true); }

// A pour interrupted by a capture and continued by a restored engine and pour state goes on
// with the bits of the pour that was not interrupted (docs/restart.md).
TEST(Pour, CapturedMidPourContinuesBitwise) {
  const SceneConfig s = pour_scene(false);
  const long before = 900, after = 1100;  // the capture between batches 4 and 5 of 10
  const PourRun whole = pour_for(s, MPI_COMM_WORLD, before + after);
  Simulation first(s, fill_container(s), MPI_COMM_WORLD);
  Pour pour(s);
  for (long k = 0; k < before; ++k) {
    pour.before_step(first);
    first.step();
  }
  ASSERT_GT(pour.state().inserted, 0);
  ASSERT_FALSE(pour.done());
  const EngineState captured = first.capture_state();
  Simulation second(s, captured, MPI_COMM_WORLD);
  Pour resumed(s, pour.state());
  for (long k = 0; k < after; ++k) {
    resumed.before_step(second);
    second.step();
  }
  const ParticleStore continued = second.whole_state();
  const double balance_error = second.energy_balance_error();  // collective
  if (test::world_rank() != 0) return;
  EXPECT_EQ(resumed.state().inserted, whole.pour.inserted);
  test::expect_bitwise_equal(continued, whole.state, "continued vs uninterrupted");
  EXPECT_EQ(balance_error, whole.balance_error);
}
