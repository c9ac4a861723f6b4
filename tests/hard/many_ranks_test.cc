// Many ranks, mostly empty: a pile of grains in one corner of a wide box, on every rank of
// MPI_COMM_WORLD (16, oversubscribed, in `ctest -L hard`; blocks 4 x 4 x 1, so 12 or more of
// them start empty and several fill as the pile collapses), gives the bits of one rank; so do
// two heaps sliding through a row of blocks, one of which empties and fills again.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "../common/scenes.h"
#include "../common/world.h"
#include "../parallel/helpers.h"
#include "dem/boundary/container.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// Soft grains (E = 50 MPa) with every effect on, in a 12 cm square box: the scene of both cases.
SceneConfig soft_grains_in_wide_box() {
  SceneConfig s = test::bare_scene(2e-5);
  s.particles.material = {2650.0, 5e7, 0.25};
  s.effects = {true, true, true, true, true, true};
  s.damping_ratio = 0.3;
  s.container.lx = s.container.ly = 0.12;
  return s;
}

}  // namespace

TEST(HardManyRanks, CornerPileOnMostlyEmptyBlocksIsBitwiseOneRank) {
  if (test::world_size() < 2) GTEST_SKIP() << "runs under mpiexec (hard.many_ranks_np16)";
  SceneConfig s = soft_grains_in_wide_box();
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

TEST(HardManyRanks, BlockEmptiedAndRefilledDuringACollapseIsBitwiseOneRank) {
  // Two 3 x 3 x 3 cubes of touching spheres thrown along x over the floor of the same box, in
  // the row of blocks y < 30 mm: each collapses into a heap as it slides. The faster one starts
  // in the second block and leaves it; the slower one, from the first block, arrives there
  // after it: that block empties and fills again. Every rank follows its own grain count
  // between chunks of steps.
  if (test::world_size() < 2) GTEST_SKIP() << "runs under mpiexec (hard.many_ranks_np16)";
  SceneConfig s = soft_grains_in_wide_box();
  std::mt19937_64 rng(13);
  ParticleStore p;
  const double r = 2e-3;
  test::add_touching_cube(p, 3, r, Vec3(0.032 + r, 9e-3 + r, r + 1e-4), Vec3(3.0, 0.0, 0.0), rng);
  test::add_touching_cube(p, 3, r, Vec3(0.003 + r, 9e-3 + r, r + 1e-4), Vec3(1.0, 0.0, 0.0), rng);
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.12, 0.12, 0.03)};
  o.blocks = {4, 4, 1};
  if (test::world_size() != 16) o.blocks = {test::world_size(), 1, 1};
  EngineOptions self = o;
  self.blocks = {1, 1, 1};
  Simulation world(s, p, make_open_box(s.container), MPI_COMM_WORLD, o);
  constexpr int kChunks = 40, kChunk = 50;
  // This block's grains: held at the start or later, then none (at step `emptied`), then some
  // again (at step `refilled`); steps to within a chunk.
  bool held = world.owned() > 0;
  long emptied = -1, refilled = -1;
  for (int k = 1; k <= kChunks; ++k) {
    world.run(kChunk);
    const bool holds = world.owned() > 0;
    if (held && !holds && emptied < 0) emptied = static_cast<long>(k) * kChunk;
    if (emptied >= 0 && holds && refilled < 0) refilled = static_cast<long>(k) * kChunk;
    held = held || holds;
  }
  long mine[2] = {emptied, refilled};
  std::vector<long> all(2 * static_cast<std::size_t>(test::world_size()));
  MPI_Gather(mine, 2, MPI_LONG, all.data(), 2, MPI_LONG, 0, MPI_COMM_WORLD);
  int blocks_refilled = 0;
  for (int q = 0; q < test::world_size(); ++q)
    if (all[2 * q + 1] >= 0) {
      ++blocks_refilled;
      if (test::world_rank() == 0)
        std::printf("block of rank %d: emptied at step %ld, filled again at step %ld\n", q, all[2 * q],
                    all[2 * q + 1]);
    }
  MPI_Bcast(&blocks_refilled, 1, MPI_INT, 0, MPI_COMM_WORLD);
  const ParticleStore parallel = world.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    std::printf("%d of %d blocks emptied and filled again\n", blocks_refilled, test::world_size());
    Simulation one(s, p, make_open_box(s.container), MPI_COMM_SELF, self);
    one.run(static_cast<long>(kChunks) * kChunk);
    test::expect_bitwise_equal(parallel, one.gather_sorted_by_id(), "emptied and refilled");
  }
  EXPECT_GE(blocks_refilled, 1);
}
