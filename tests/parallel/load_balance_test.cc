// Dynamic load balance (docs/parallel.md, "Load balance"): the planes move to the cost
// quantiles and cut the imbalance of a one-sided bed; the results stay bitwise equal to one
// rank; a plane moved by more than a block width loses no particle (several migration
// passes, springs included); interior blocks never get thinner than the interaction range.
#include <gtest/gtest.h>

#include <mpi.h>
#include <array>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "../common/scenes.h"
#include "dem/core/error.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// No gravity, no walls: grains only move as they are set moving.
SceneConfig free_scene() {
  SceneConfig s = test::bare_scene(1e-5);
  s.effects = {false, true, true, false, true, true};
  s.damping_ratio = 0.1;
  s.neighbor_skin = 0.2;
  return s;
}

// A jittered lattice of n[0] x n[1] x n[2] spheres (radius r, pitch 2.2 r, no overlaps)
// from `corner`, with random velocities of up to `speed` and spins.
ParticleStore lattice(const std::array<int, 3>& n, double r, const Vec3& corner, double speed,
                      std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ParticleStore p;
  const double pitch = 2.2 * r;
  for (int a = 0; a < n[0]; ++a)
    for (int b = 0; b < n[1]; ++b)
      for (int c = 0; c < n[2]; ++c) {
        const Vec3 jitter = 0.04 * r * Vec3(u(rng), u(rng), u(rng));
        p.add_sphere(static_cast<GlobalId>(p.size()), r, 2650, corner + pitch * Vec3(a, b, c) + jitter,
                     speed * Vec3(u(rng), u(rng), u(rng)), 50.0 * Vec3(u(rng), u(rng), u(rng)));
      }
  return p;
}

long global_sum(long v) {
  long s = 0;
  MPI_Allreduce(&v, &s, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return s;
}

// Steps until a neighbour-list rebuild has happened in the last step: ownership changes
// only there (in between, grains drift up to half a skin across the planes), and the
// positions after that step are those the owners were chosen by.
void step_to_next_rebuild(Simulation& sim) {
  const long rebuilds = sim.rank_diagnostics().rebuilds;
  for (int k = 0; k < 2000 && sim.rank_diagnostics().rebuilds == rebuilds; ++k) sim.step();
  ASSERT_GT(sim.rank_diagnostics().rebuilds, rebuilds);
}

// Right after a rebuild: every owned particle sits in this rank's block, and the gathered
// state holds each id 0 .. n - 1 once.
void expect_every_particle_home_once(const Simulation& sim, long n) {
  const Decomposition& dec = sim.decomposition();
  long strays = 0;
  for (int i = 0; i < sim.owned(); ++i) strays += dec.owner_of(sim.particles().x[i]) == dec.rank() ? 0 : 1;
  EXPECT_EQ(global_sum(strays), 0);
  EXPECT_EQ(global_sum(sim.owned()), n);
  const ParticleStore all = sim.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    ASSERT_EQ(static_cast<long>(all.size()), n);
    for (long k = 0; k < n; ++k) ASSERT_EQ(all.id[k], k);
  }
}

}  // namespace

// (a) 9 x 9 x 27 grains in one corner column of a 60 mm box: on the chosen blocks (2x1x1,
// 3x1x1, 2x2x1) one block owns all of them, an imbalance of K. The planes move into the
// column at construction and at later rebuilds, and the imbalance falls below 1.1 (bound
// stated in docs/parallel.md).
TEST(LoadBalance, CornerColumnImbalanceFallsBelowBound) {
  const int size = test::world_size();
  const SceneConfig s = free_scene();
  std::mt19937_64 rng(21);
  const ParticleStore p = lattice({9, 9, 27}, 1e-3, Vec3(1.1e-3, 1.1e-3, 1.1e-3), 0.2, rng);
  const long n = static_cast<long>(p.size());
  EngineOptions fixed;
  fixed.box = Box{Vec3::Zero(), Vec3(0.06, 0.06, 0.06)};
  EngineOptions balanced = fixed;
  balanced.balance_interval = 50;
  Simulation still(s, p, {}, MPI_COMM_WORLD, fixed);
  Simulation moving(s, p, {}, MPI_COMM_WORLD, balanced);
  // Balanced at construction: the column's blocks owned everything. On up to 4 ranks the
  // chosen blocks do not cut z, so one block owns it all (an imbalance of K); on 8 ranks
  // (2x2x2) two blocks share it (K/2).
  const double initial = still.load_imbalance().owned_ratio;
  const RankDiagnostics d0 = moving.rank_diagnostics();
  EXPECT_EQ(d0.rebalances, 1);
  EXPECT_NEAR(d0.imbalance_before, initial, 1e-12);
  if (size <= 4) {
    EXPECT_NEAR(initial, size, 1e-12);
  }
  EXPECT_LT(d0.imbalance_after, 1.1);
  still.run(400);
  moving.run(400);
  const LoadImbalance a = still.load_imbalance();
  const LoadImbalance b = moving.load_imbalance();
  const RankDiagnostics d = moving.rank_diagnostics();
  if (test::world_rank() == 0)
    std::printf(
        "corner column, %d ranks: %ld rebuilds, %ld rebalances; owned max/mean fixed %.3f, balanced %.3f "
        "(last rebalance at step %ld: %.3f -> %.3f)\n",
        size, d.rebuilds, d.rebalances, a.owned_ratio, b.owned_ratio, d.rebalance_step, d.imbalance_before,
        d.imbalance_after);
  EXPECT_EQ(still.rank_diagnostics().rebalances, 0);
  EXPECT_GE(d.rebalances, 2);  // rebuilds happen about every 100 steps here
  step_to_next_rebuild(moving);
  expect_every_particle_home_once(moving, n);
  if (size == 1) {
    EXPECT_EQ(b.owned_ratio, 1.0);
    return;
  }
  EXPECT_GT(a.owned_ratio, 0.95 * initial);  // without balance the column stays where it was
  EXPECT_LT(b.owned_ratio, 1.1);
  EXPECT_LT(d.imbalance_after, 1.1);
  EXPECT_GE(d.imbalance_before, 1.0);
}

// (b) The 600-sphere deposition with the planes along z moving every 200 steps as the
// grains fall and settle: bitwise equal to one rank, no particle lost.
TEST(LoadBalance, DepositionWithBalancingIsBitwiseIdentical) {
  const int size = test::world_size();
  const SceneConfig s = test::deposition_scene(600);
  const ParticleStore p = fill_container(s);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  EngineOptions o;
  // Blocks along z (the grains fall through the planes); above 4 ranks z blocks would be
  // thinner than the interaction range in this 20 mm fill, so x is cut in two as well.
  o.blocks = size > 4 && size % 2 == 0 ? std::array<int, 3>{2, 1, size / 2} : std::array<int, 3>{1, 1, size};
  o.balance_interval = 200;
  Simulation world(s, p, walls, MPI_COMM_WORLD, o);
  const Decomposition& dec = world.decomposition();
  const int nz = o.blocks[2];
  std::vector<double> start(static_cast<std::size_t>(nz + 1));
  for (int k = 0; k <= nz; ++k) start[k] = dec.plane(2, k);
  world.run(3000);
  const RankDiagnostics d = world.rank_diagnostics();
  double shift = 0.0;
  for (int k = 0; k <= nz; ++k) shift = std::max(shift, std::abs(dec.plane(2, k) - start[k]));
  const long migrated = global_sum(d.migrated_out);
  const ParticleStore parallel = world.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    std::printf(
        "balanced deposition, %d ranks (%dx1x%d): %ld rebuilds, %ld rebalances, %ld migrations, largest "
        "plane shift %.2f mm; last rebalance %.3f -> %.3f\n",
        size, o.blocks[0], o.blocks[2], d.rebuilds, d.rebalances, migrated, 1e3 * shift, d.imbalance_before,
        d.imbalance_after);
    EngineOptions self;
    self.balance_interval = 200;
    Simulation one(s, p, walls, MPI_COMM_SELF, self);
    one.run(3000);
    const ParticleStore serial = one.gather_sorted_by_id();
    EXPECT_EQ(parallel.size(), p.size());
    EXPECT_EQ(one.rank_diagnostics().rebalances, d.rebalances);
    test::expect_bitwise_equal(parallel, serial, std::to_string(size) + " balanced ranks vs 1");
  }
  EXPECT_GE(d.rebalances, 10);
  if (size > 1) {
    EXPECT_GT(shift, 2e-3);  // the grains fall: the planes follow them down
    EXPECT_GT(migrated, 0);
  }
}

// (b') The patch test balanced by pair slots on the chosen blocks: bitwise equal to one rank.
TEST(LoadBalance, PatchTestBalancedByPairSlotsIsBitwiseIdentical) {
  const SceneConfig s = test::patch_scene();
  const ParticleStore p = fill_container(s);
  EngineOptions o;
  o.balance_interval = 40;
  o.balance_cost = BalanceCost::pair_slots;
  const RankDiagnostics d = test::expect_rank_independent(s, p, make_open_box(s.container), o, o, 300);
  EXPECT_GE(d.rebalances, 2);
}

// (c) A 4 x 4 x 4 cube of touching, spinning grains in the last of K blocks along x, moving
// fast along y (not cut) so that the first rebuild, and rebalance, comes while they touch.
// The planes move into the cube: plane 1 by more than a block width (K >= 3), and grains
// travel K - 1 blocks in several passes with their springs. None is lost, and the run stays
// bitwise equal to one rank (a lost spring would change it).
TEST(LoadBalance, PlaneMovedByMoreThanABlockLosesNoParticle) {
  const int size = test::world_size();
  const SceneConfig s = free_scene();
  std::mt19937_64 rng(9);
  ParticleStore p;
  test::add_touching_cube(p, 4, 2e-3, Vec3(0.0465, 0.004, 0.008), Vec3(0.0, 8.0, 0.0), rng);
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.06, 0.03, 0.03)};
  o.blocks = {size, 1, 1};
  o.balance_interval = 1;
  o.balance_at_start = false;  // the first rebalance comes with springs to carry
  Simulation sim(s, p, {}, MPI_COMM_WORLD, o);
  const double plane1 = sim.decomposition().plane(0, 1);
  // Step until the first rebalance, recording the contacts of the step that made it.
  long steps = 0;
  while (sim.rank_diagnostics().rebalances == 0 && steps < 100) {
    sim.request_contacts();
    sim.step();
    ++steps;
  }
  long touching = 0;
  for (const ContactSample& c : sim.contacts()) touching += c.with_wall() ? 0 : 1;
  touching = global_sum(touching);
  const double shift = sim.decomposition().plane(0, 1) - plane1;
  const long migrated = global_sum(sim.rank_diagnostics().migrated_out);
  // Home right after the rebuild that moved the planes (the step ends with its positions).
  expect_every_particle_home_once(sim, 64);
  sim.run(200 - steps);
  const RankDiagnostics d = sim.rank_diagnostics();
  if (test::world_rank() == 0)
    std::printf(
        "cube: first rebalance at step %ld with %ld touching pair slots; plane 1 moved %.1f mm (block width "
        "%.1f mm), %ld hops; %ld rebalances in 200 steps\n",
        steps, touching, 1e3 * shift, 60.0 / size, migrated, d.rebalances);
  EXPECT_GE(d.rebalances, 2);
  EXPECT_GT(touching, 0);  // springs existed when the grains moved
  if (size >= 3) {
    EXPECT_GT(shift, 0.06 / size);
    // The first layer (16 grains) alone makes K - 1 hops while the cube (16 mm) sits in the
    // last block (K <= 4); with thinner blocks it starts across the last three (K = 8).
    EXPECT_GE(migrated, size <= 4 ? 16L * (size - 1) : 16L * (size - 3));
  }
  const ParticleStore parallel = sim.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    EngineOptions self = o;
    self.blocks = {1, 1, 1};
    Simulation one(s, p, {}, MPI_COMM_SELF, self);
    one.run(200);
    test::expect_bitwise_equal(parallel, one.gather_sorted_by_id(), "plane moved past blocks");
  }
  step_to_next_rebuild(sim);
  expect_every_particle_home_once(sim, 64);
}

// (d) A sheet of grains one grain thick across x: the quantiles of every cut coincide, and
// the clamp spreads them so that every interior block is at least the interaction range
// thick (exactly, as Decomposition checks). Explicit thin cuts are refused.
TEST(LoadBalance, ThinSheetKeepsInteriorBlocksAtLeastTheRangeThick) {
  const int size = test::world_size();
  const SceneConfig s = free_scene();
  std::mt19937_64 rng(4);
  const ParticleStore p = lattice({1, 12, 12}, 1e-3, Vec3(0.0301, 0.001, 0.001), 0.2, rng);
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.06, 0.03, 0.03)};
  o.blocks = {size, 1, 1};
  o.balance_interval = 20;
  Simulation sim(s, p, {}, MPI_COMM_WORLD, o);
  sim.run(300);
  const Decomposition& dec = sim.decomposition();
  const double range = sim.interaction_range();
  EXPECT_GE(sim.rank_diagnostics().rebalances, 1);
  for (int k = 1; k < size; ++k) {
    EXPECT_GE(dec.plane(0, k), 0.0);
    EXPECT_LE(dec.plane(0, k), 0.06);
    EXPECT_GE(dec.plane(0, k), dec.plane(0, k - 1));
    if (k >= 2) {
      EXPECT_GE(dec.plane(0, k) - dec.plane(0, k - 1), range) << "interior block " << k - 1;
    }
  }
  if (size >= 3) {
    // Without the clamp the cuts would lie within the sheet, thinner than the range.
    EXPECT_LT(dec.plane(0, 1), 0.0301 + 0.5 * range);
    EXPECT_NEAR(dec.plane(0, 2) - dec.plane(0, 1), range, 1e-12);
    std::vector<double> thin(static_cast<std::size_t>(size - 1));
    for (int k = 0; k < size - 1; ++k) thin[k] = 0.03 + 0.5 * range * k;
    Decomposition check(MPI_COMM_WORLD, *o.box, range, o.blocks);
    try {
      check.set_cuts(0, thin);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("thinner than the interaction range"), std::string::npos)
          << e.what();
    }
  }
  const ParticleStore parallel = sim.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    EngineOptions self = o;
    self.blocks = {1, 1, 1};
    Simulation one(s, p, {}, MPI_COMM_SELF, self);
    one.run(300);
    test::expect_bitwise_equal(parallel, one.gather_sorted_by_id(), "thin sheet");
  }
  step_to_next_rebuild(sim);
  expect_every_particle_home_once(sim, static_cast<long>(p.size()));
}
