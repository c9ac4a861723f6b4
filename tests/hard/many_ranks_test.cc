// Many ranks, mostly empty: a pile of grains in one corner of a wide box, on every rank of
// MPI_COMM_WORLD (16, oversubscribed, in `ctest -L hard`; blocks 4 x 4 x 1, so 12 or more of
// them start empty and several fill as the pile collapses), gives the bits of one rank.
#include <gtest/gtest.h>

#include <random>

#include "../common/scenes.h"
#include "../common/world.h"
#include "../parallel/helpers.h"
#include "dem/boundary/container.h"

using namespace upgrain;
using namespace upgrain::dem;

TEST(HardManyRanks, CornerPileOnMostlyEmptyBlocksIsBitwiseOneRank) {
  if (test::world_size() < 2) GTEST_SKIP() << "runs under mpiexec (hard.many_ranks_np16)";
  SceneConfig s = test::bare_scene(2e-5);
  s.particles.material = {2650.0, 5e7, 0.25};
  s.effects = {true, true, true, true, true, true};
  s.damping_ratio = 0.3;
  s.container.lx = s.container.ly = 0.12;
  std::mt19937_64 rng(11);
  ParticleStore p;
  const double r = 2e-3;
  // 3 x 3 x 3 touching spheres, spinning, with a sideways push, in the corner at the origin.
  test::add_touching_cube(p, 3, r, Vec3(r, r, r + 1e-4), Vec3(0.5, 0.3, 0.0), rng);
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.12, 0.12, 0.03)};
  o.blocks = {4, 4, 1};
  if (test::world_size() != 16) o.blocks = {test::world_size(), 1, 1};
  EngineOptions self = o;
  self.blocks = {1, 1, 1};
  const RankDiagnostics d = test::expect_rank_independent(s, p, make_open_box(s.container), o, self, 3000);
  int owned_at_end = d.owned > 0 ? 1 : 0, blocks_with_grains = 0;
  MPI_Allreduce(&owned_at_end, &blocks_with_grains, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (test::world_rank() == 0)
    std::printf("%d of %d blocks hold grains at the end\n", blocks_with_grains, test::world_size());
  EXPECT_GE(blocks_with_grains, 2) << "the pile spread across a block face";
  EXPECT_LE(blocks_with_grains, test::world_size() / 2) << "most blocks stayed empty";
}
