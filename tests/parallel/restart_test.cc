// Restart of the engine (dem/engine/engine_state.h, docs/restart.md): a run captured between
// two steps and continued from the captured state, on the same or another number of ranks,
// ends with the same bits as the run that was not interrupted (deterministic summation):
// positions, velocities, spins and orientations, energies with the dissipation, wall forces,
// contact counts and the number of list rebuilds.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "dem/boundary/container.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "helpers.h"
#include "tests/common/relaxed_bed.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// Everything the comparison looks at after a run.
struct Outcome {
  ParticleStore state;  // rank 0
  EnergyBalance energy;
  std::vector<Vec3> wall_forces;
  StepDiagnostics diagnostics;
  Mat3 cell, velocity_gradient, cell_stress;  // a deforming cell's
};

Outcome outcome(Simulation& sim) {
  Outcome o;
  o.state = sim.gather_sorted_by_id();
  o.energy = sim.energy();
  o.wall_forces = sim.wall_forces();
  o.diagnostics = sim.diagnostics();
  o.cell = sim.cell_matrix();
  o.velocity_gradient = sim.cell_velocity_gradient();
  o.cell_stress = sim.cell_stress();
  return o;
}

void expect_same(const Outcome& a, const Outcome& b, const std::string& what) {
  if (test::world_rank() != 0) return;
  test::expect_bitwise_equal(a.state, b.state, what);
  EXPECT_EQ(a.state.force, b.state.force) << what;
  const EnergyBalance &x = a.energy, &y = b.energy;
  for (auto [u, v, name] :
       {std::tuple{x.kinetic(), y.kinetic(), "kinetic"},
        {x.potential, y.potential, "potential"},
        {x.elastic_normal, y.elastic_normal, "elastic normal"},
        {x.elastic_tangential, y.elastic_tangential, "elastic tangential"},
        {x.dissipated_damping, y.dissipated_damping, "damping"},
        {x.dissipated_friction, y.dissipated_friction, "friction"},
        {x.tangential_stiffness_change, y.tangential_stiffness_change, "stiffness change"},
        {x.dissipated_rolling, y.dissipated_rolling, "rolling"},
        {x.work_by_walls, y.work_by_walls, "walls' work"},
        {x.work_by_cell, y.work_by_cell, "cell's work"}})
    EXPECT_EQ(u, v) << what << ": " << name << " energy";
  EXPECT_EQ(a.wall_forces, b.wall_forces) << what;
  EXPECT_EQ(a.cell, b.cell) << what;
  EXPECT_EQ(a.velocity_gradient, b.velocity_gradient) << what;
  EXPECT_EQ(a.cell_stress, b.cell_stress) << what;
  EXPECT_EQ(a.diagnostics.particle_contacts, b.diagnostics.particle_contacts) << what;
  EXPECT_EQ(a.diagnostics.wall_contacts, b.diagnostics.wall_contacts) << what;
  EXPECT_EQ(a.diagnostics.neighbor_builds, b.diagnostics.neighbor_builds) << what;
  EXPECT_EQ(a.diagnostics.max_overlap_ratio, b.diagnostics.max_overlap_ratio) << what;
}

// The scene run for `first` steps on all ranks, captured, and continued for `then` steps:
// (1) without interruption on all ranks; (2) from the state on all ranks; (3) from the state on
// rank 0 alone; (4) captured on all ranks but the last and continued on all of them (one rank
// more: 1 -> 2, 2 -> 3, ...). Every continuation must give the bits of (1).
void expect_restart_is_bitwise(const SceneConfig& s, long first, long then, const std::string& what,
                               bool one_rank_more = true, const std::vector<PlaneWall>& more_walls = {}) {
  const ParticleStore fill = fill_container(s);
  std::vector<PlaneWall> walls = make_open_box(s.container);
  walls.insert(walls.end(), more_walls.begin(), more_walls.end());
  // (1) and the state at `first` on all ranks.
  Simulation world(s, fill, walls, MPI_COMM_WORLD);
  world.run(first);
  const EngineState at_first = world.capture_state();
  world.run(then);
  const Outcome reference = outcome(world);
  if (test::world_rank() == 0) {
    std::printf(
        "%s: %ld + %ld steps on %d ranks, %ld rebuilds, %ld contacts, %zu histories at the capture, "
        "%ld wall contacts\n",
        what.c_str(), first, then, test::world_size(), reference.diagnostics.neighbor_builds,
        reference.diagnostics.particle_contacts, at_first.history.size(),
        reference.diagnostics.wall_contacts);
    ASSERT_EQ(at_first.step, first);
    for (std::size_t w = walls.size() - more_walls.size(); w < walls.size(); ++w)
      EXPECT_NE(reference.wall_forces[w], Vec3::Zero()) << walls[w].name << " touches the grains";
  }
  // (2) all ranks from the state.
  {
    Simulation resumed(s, at_first, MPI_COMM_WORLD);
    resumed.run(then);
    expect_same(outcome(resumed), reference, what + ", resumed on all ranks");
  }
  // (3) rank 0 alone.
  if (test::world_rank() == 0) {
    Simulation alone(s, at_first, MPI_COMM_SELF);
    alone.run(then);
    Outcome o = outcome(alone);
    expect_same(o, reference, what + ", resumed on one rank");
  }
  // (4) one rank fewer before the capture than after it.
  if (one_rank_more && test::world_size() > 1) {
    MPI_Comm fewer;
    const bool in = test::world_rank() < test::world_size() - 1;
    MPI_Comm_split(MPI_COMM_WORLD, in ? 0 : MPI_UNDEFINED, test::world_rank(), &fewer);
    EngineState captured;
    if (in) {
      {
        Simulation before(s, fill, walls, fewer);
        before.run(first);
        captured = before.capture_state();
      }
      MPI_Comm_free(&fewer);
    }
    Simulation after(s, captured, MPI_COMM_WORLD);
    after.run(then);
    expect_same(outcome(after), reference,
                what + ", " + std::to_string(test::world_size() - 1) + " ranks then " +
                    std::to_string(test::world_size()));
  }
}

TEST(Restart, SphereDepositionContinuesBitwise) {
  SceneConfig s = test::deposition_scene(300);
  expect_restart_is_bitwise(s, 2500, 1500, "300 spheres");
}

// A bed without side walls (periodic x and y over the floor, docs/periodic.md): the image
// counters and the periodic flags travel in the state, and grains cross the faces on both sides
// of the capture.
TEST(Restart, PeriodicBedContinuesBitwise) {
  SceneConfig s = test::deposition_scene(240);
  s.container.periodic = {true, true, false};
  s.fill.velocity = Vec3(0.4, -0.3, -0.5);
  expect_restart_is_bitwise(s, 1500, 1000, "240 spheres, periodic x and y");
}

// A cell that deforms (docs/periodic.md, "A cell that deforms"), squeezed along x at a rate and
// along y by a servo: its box, its box at the last list build, L (the servo's state), its stress
// and its work travel in the state, and the run goes on with the bits of the one not interrupted.
TEST(Restart, DeformingCellContinuesBitwise) {
  expect_restart_is_bitwise(test::compressing_cell_scene(240, Vec3(0.4, -0.3, -0.5)), 1500, 1000,
                            "240 spheres in a deforming cell");
}

// The same cell sheared along x with the gradient y (docs/periodic.md, "Shear"): the sliding
// images' offset, its turns and its offset at the last build travel in the state too.
TEST(Restart, ShearedCellContinuesBitwise) {
  SceneConfig s = test::compressing_cell_scene(240, Vec3(0.4, -0.3, -0.5));
  s.cell.shear = {{0, 1}, 40.0};
  expect_restart_is_bitwise(s, 1500, 1000, "240 spheres in a sheared cell");
}

TEST(Restart, RollingResistanceContinuesBitwise) {
  SceneConfig s = test::deposition_scene(200);
  s.effects.rolling_resistance = true;
  s.rolling_friction = 0.1;
  s.rolling_damping_ratio = 0.3;
  s.effects.twisting_resistance = true;  // its spring travels in the same history record
  expect_restart_is_bitwise(s, 2000, 1000, "200 spheres, rolling and twisting resistance");
}

TEST(Restart, EllipsoidsAndAMixContinueBitwise) {
  SceneConfig s = test::paper_ellipsoid_bed_scene(120);
  s.fill.velocity = Vec3(0, 0, -1.0);
  s.fill.velocity_jitter = 0.5;
  expect_restart_is_bitwise(s, 16000, 3000, "120 paper ellipsoids");
  s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 3.0), ellipsoid_grain(0.6, 0.4, 1.0)};
  expect_restart_is_bitwise(s, 16000, 3000, "120 spheres and flat ellipsoids", false);
}

// A lid coming down onto the falling grains and a floor sliding under them (docs/scenes.md,
// "Moving walls"): the walls' positions, velocities and work continue bitwise.
TEST(Restart, MovingWallsContinueBitwise) {
  SceneConfig s = test::deposition_scene(240);
  const ParticleStore fill = fill_container(s);
  double top = 0.0;
  for (std::size_t i = 0; i < fill.size(); ++i) top = std::max(top, fill.x[i].z() + fill.radius[i]);
  PlaneWall lid{"lid", Vec3(0, 0, top + 1e-3), Vec3(0, 0, -1), 0.5};
  lid.velocity = Vec3(0, 0, -0.1);
  PlaneWall belt{"belt", Vec3(0, 0, 1e-4), Vec3(0, 0, 1), 0.5};  // just above the box's floor
  belt.velocity = Vec3(0.05, 0.02, 0);
  expect_restart_is_bitwise(s, 2500, 1500, "240 spheres, moving lid and belt", true, {lid, belt});
}

// A gate that opens between the capture and the end: the wall removed after the restart, and a
// capture after it opened (the removed wall in the state).
TEST(Restart, ContinuesAcrossAndAfterAGateOpening) {
  SceneConfig s = test::deposition_scene(240);
  s.container.gate_x = 0.6 * s.container.lx;
  s.container.gate_open_time = 0.03;
  const ParticleStore fill = fill_container(s);
  const long open_step = static_cast<long>(s.container.gate_open_time / s.time_step);
  auto run_with_gate = [&](Simulation& sim, long steps) {
    for (long k = 0; k < steps; ++k) {
      if (sim.step_count() == open_step) sim.remove_wall(kGateWallName);
      sim.step();
    }
  };
  for (const long first : {open_step - 500, open_step + 300}) {
    Simulation world(s, fill, make_open_box(s.container), MPI_COMM_WORLD);
    run_with_gate(world, first);
    const EngineState state = world.capture_state();
    run_with_gate(world, open_step + 1500 - first);
    const Outcome reference = outcome(world);
    Simulation resumed(s, state, MPI_COMM_WORLD);
    run_with_gate(resumed, open_step + 1500 - first);
    expect_same(outcome(resumed), reference, "gate, captured at step " + std::to_string(first));
    if (test::world_rank() == 0) {
      Simulation alone(s, state, MPI_COMM_SELF);
      run_with_gate(alone, open_step + 1500 - first);
      expect_same(outcome(alone), reference, "gate on one rank, captured at step " + std::to_string(first));
    }
  }
}

// A bed captured on one rank and continued on all (docs/restart.md, docs/parallel.md "Load
// balance"): the restored engine balances its planes over the grains at once, as a fresh run
// does at its first rebuild. With the default planes of the box, the grains lie in its lower
// blocks, and a bed at rest is never rebuilt, so it was never rebalanced (owned max/mean 2 on 2
// ranks, 99.8 % of the step time in communication). The continuation stays bitwise equal to the
// run balanced on all ranks from the start.
TEST(Restart, OnMoreRanksTheBedIsBalancedAtOnce) {
  // The slabs of each cut axis are balanced to the grain; the blocks of several cut axes (8
  // ranks: 2 x 2 x 2) only as well as the grains' positions are uncorrelated across the axes.
  const double bound = 1.1;
  if (test::world_size() == 1) GTEST_SKIP() << "one rank: nothing to balance";
  // A narrow column thrown down: its box (floor to the fill's top, 7.5 cm) is cut along z, and
  // by the capture the grains have settled into its lower half.
  SceneConfig s = test::deposition_scene(200);
  s.container.lx = s.container.ly = 0.012;
  s.fill.velocity = Vec3(0, 0, -1.0);
  EngineOptions balanced;
  balanced.balance_interval = 200;
  const long first = 10000, then = 1500;
  const ParticleStore fill = fill_container(s);
  Simulation world(s, fill, MPI_COMM_WORLD, balanced);
  world.run(first + then);
  const Outcome reference = outcome(world);
  EngineState captured;
  if (test::world_rank() == 0) {
    Simulation alone(s, fill, MPI_COMM_SELF, balanced);
    alone.run(first);
    captured = alone.capture_state();
  }
  double with_default_planes = 0.0;
  {
    EngineOptions fixed = balanced;
    fixed.balance_interval = 0;
    Simulation unbalanced(s, captured, MPI_COMM_WORLD, fixed);
    with_default_planes = unbalanced.load_imbalance().owned_ratio;
  }
  Simulation resumed(s, captured, MPI_COMM_WORLD, balanced);
  const LoadImbalance at_restart = resumed.load_imbalance();
  const RankDiagnostics d = resumed.rank_diagnostics();
  if (test::world_rank() == 0)
    std::printf(
        "captured on 1 rank at step %ld, restored on %d: owned max/mean %.3f with the default planes, "
        "%.3f balanced (rebalance %ld at step %ld: %.3f -> %.3f)\n",
        first, test::world_size(), with_default_planes, at_restart.owned_ratio, d.rebalances,
        d.rebalance_step, d.imbalance_before, d.imbalance_after);
  EXPECT_GT(with_default_planes, 1.5) << "the case: the default planes leave ranks idle";
  EXPECT_LT(at_restart.owned_ratio, bound);
  EXPECT_EQ(d.rebalance_step, first);
  EXPECT_NEAR(d.imbalance_after, at_restart.owned_ratio, 1e-12);
  resumed.run(then);
  expect_same(outcome(resumed), reference,
              "1 rank then " + std::to_string(test::world_size()) + ", balanced");
}

}  // namespace
