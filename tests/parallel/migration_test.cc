// Migration: particles crossing faces, edges and corners of blocks in the same step; a
// block emptied and refilled; the diagnosis of a particle jumping past a block.
#include <gtest/gtest.h>
#include <mpi.h>

#include <random>

#include "../common/scenes.h"
#include "dem/core/error.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

SceneConfig free_scene() {
  SceneConfig s = test::bare_scene(1e-5);
  s.effects = {false, true, true, false, true, true};  // no gravity, no walls
  s.damping_ratio = 0.1;
  s.neighbor_skin = 0.2;
  return s;
}

}  // namespace

TEST(Migration, CrossingFacesEdgesAndCornersInTheSameStep) {
  // A 4 x 4 x 4 cube moving along the diagonal through the centre of a 60 mm box: on 4
  // ranks (2 x 2 x 1 blocks) it crosses both planes, their edge, at once.
  const SceneConfig s = free_scene();
  std::mt19937_64 rng(3);
  ParticleStore p;
  const double r = 2e-3;
  test::add_touching_cube(p, 4, r, Vec3(0.022, 0.022, 0.022), Vec3(2.0, 2.0, 2.0), rng);
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.06, 0.06, 0.06)};
  const RankDiagnostics d = test::expect_rank_independent(s, p, {}, o, o, 800);
  long migrated = 0;
  MPI_Allreduce(&d.migrated_out, &migrated, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (test::world_size() > 1) {
    EXPECT_GE(migrated, 48);  // three of the four layers cross a plane at x = 30 mm or 40 mm
  }
}

TEST(Migration, BlockEmptiedAndRefilled) {
  // Two clusters pass each other along x through every block of a row of K blocks: the
  // first block loses cluster A, is empty for a while, and receives cluster B.
  const SceneConfig s = free_scene();
  std::mt19937_64 rng(5);
  ParticleStore p;
  const double r = 2e-3;
  test::add_touching_cube(p, 3, r, Vec3(0.004, 0.011, 0.011), Vec3(5.0, 0, 0), rng);
  // B starts beyond the box's end: the outer blocks are open.
  test::add_touching_cube(p, 3, r, Vec3(0.070, 0.011, 0.041), Vec3(-5.0, 0, 0), rng);
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.06, 0.03, 0.06)};
  o.blocks = {test::world_size(), 1, 1};
  EngineOptions self = o;
  self.blocks = {1, 1, 1};
  Simulation sim(s, p, {}, MPI_COMM_WORLD, o);
  const bool first_block = sim.decomposition().coords()[0] == 0;
  bool emptied = !first_block, refilled = !first_block;
  for (int k = 0; k < 26; ++k) {
    sim.run(50);
    if (first_block && sim.owned() == 0) emptied = true;
    if (first_block && emptied && sim.owned() > 0) refilled = true;
  }
  if (test::world_size() > 1) {
    EXPECT_TRUE(emptied);
    EXPECT_TRUE(refilled);
  }
  const ParticleStore parallel = sim.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    Simulation one(s, p, {}, MPI_COMM_SELF, self);
    one.run(1300);
    test::expect_bitwise_equal(parallel, one.gather_sorted_by_id(), "emptied and refilled");
  }
}

TEST(Migration, ParticleJumpingPastABlockStopsTheRunOnEveryRank) {
  const int size = test::world_size();
  if (size < 3) GTEST_SKIP() << "needs at least 3 blocks in a row";
  SceneConfig s = free_scene();
  ParticleStore p;
  p.add_sphere(0, 2e-3, 2650, Vec3(0.030, 0.015, 0.015), Vec3::Zero(), Vec3::Zero());
  // 4 km/s: 40 mm in one step of 10 us, past the whole next block.
  p.add_sphere(7, 2e-3, 2650, Vec3(0.005, 0.015, 0.015), Vec3(4000.0, 0, 0), Vec3::Zero());
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.06, 0.03, 0.03)};
  o.blocks = {size, 1, 1};
  Simulation sim(s, p, {}, MPI_COMM_WORLD, o);
  try {
    sim.run(5);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("particle 7 "), std::string::npos) << m;
    EXPECT_NE(m.find("farther than one block"), std::string::npos) << m;
    EXPECT_NE(m.find("block (0, 0, 0)"), std::string::npos) << m;
  }
}
