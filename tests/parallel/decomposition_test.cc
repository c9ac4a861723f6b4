// The decomposition rule, ownership, the refusal of thin blocks, and the ghost set: on
// every rank, the owned particles and ghosts hold exactly the partners a brute-force
// all-pairs search finds within r_i + r_j + skin of each owned particle.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <random>

#include "../common/scenes.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

TEST(Decomposition, BlockChoiceMinimisesCutArea) {
  const Box cube{Vec3::Zero(), Vec3(1, 1, 1)};
  EXPECT_EQ(choose_blocks(1, cube, 0.1), (std::array<int, 3>{1, 1, 1}));
  EXPECT_EQ(choose_blocks(2, cube, 0.1), (std::array<int, 3>{2, 1, 1}));
  EXPECT_EQ(choose_blocks(4, cube, 0.1), (std::array<int, 3>{2, 2, 1}));
  EXPECT_EQ(choose_blocks(8, cube, 0.1), (std::array<int, 3>{2, 2, 2}));
  // A tall column is cut across its height; a flat bed across its width.
  const Box column{Vec3::Zero(), Vec3(1, 1, 8)};
  EXPECT_EQ(choose_blocks(4, column, 0.1), (std::array<int, 3>{1, 1, 4}));
  const Box bed{Vec3::Zero(), Vec3(4, 1, 0.5)};
  EXPECT_EQ(choose_blocks(4, bed, 0.1), (std::array<int, 3>{4, 1, 1}));
  // Blocks thinner than the interaction range are never chosen...
  EXPECT_EQ(choose_blocks(4, bed, 0.3), (std::array<int, 3>{4, 1, 1}));
  EXPECT_EQ(choose_blocks(4, Box{Vec3::Zero(), Vec3(1, 1, 1)}, 0.4), (std::array<int, 3>{2, 2, 1}));
  // ...and when no arrangement fits, the error names the sizes.
  try {
    (void)choose_blocks(4, Box{Vec3::Zero(), Vec3(1, 1, 1)}, 0.6);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("0.6"), std::string::npos) << e.what();
  }
}

TEST(Decomposition, OwnershipCoversSpaceAndThinBlocksAreRefused) {
  const int size = test::world_size();
  const Box box{Vec3(0, 0, 0), Vec3(0.06, 0.06, 0.06)};
  Decomposition dec(MPI_COMM_WORLD, box, 0.005);
  EXPECT_EQ(dec.blocks()[0] * dec.blocks()[1] * dec.blocks()[2], size);
  // Points on planes, outside the box (open outer faces) and inside: exactly one owner,
  // and the owner's block contains the point.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.02, 0.08);
  for (int k = 0; k < 2000; ++k) {
    Vec3 x(u(rng), u(rng), u(rng));
    if (k % 3 == 0) x[0] = dec.plane(0, std::min(1, dec.blocks()[0]));
    const std::array<int, 3> c = dec.block_of(x);
    int mine = dec.owner_of(x) == dec.rank() ? 1 : 0;
    int owners = 0;
    MPI_Allreduce(&mine, &owners, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    ASSERT_EQ(owners, 1);
    if (c == dec.coords()) {
      for (int d = 0; d < 3; ++d) {
        EXPECT_GE(x[d], dec.block().lo[d]);
        EXPECT_LT(x[d], dec.block().hi[d]);
      }
    }
  }
  // Explicit blocks thinner than the range: refused on every rank, naming the sizes.
  if (size > 1) {
    try {
      Decomposition thin(MPI_COMM_WORLD, box, 0.05, {size, 1, 1});
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("thinner along x"), std::string::npos) << e.what();
    }
  }
}

TEST(Ghosts, CoverEveryPairWithinRangeExactlyOnce) {
  // Random spheres (overlaps allowed: no step is taken) in and around a cube.
  const double r_max = 2e-3;
  SceneConfig s = test::bare_scene(1e-5);
  s.neighbor_skin = 0.2;
  ParticleStore all;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.002, 0.062), ur(0.5 * r_max, r_max);
  for (int k = 0; k < 3000; ++k)
    all.add_sphere(k, k == 0 ? r_max : ur(rng), 2650, Vec3(u(rng), u(rng), u(rng)), Vec3::Zero(),
                   Vec3::Zero());
  EngineOptions o;
  o.box = Box{Vec3::Zero(), Vec3(0.06, 0.06, 0.06)};
  Simulation sim(s, all, {}, MPI_COMM_WORLD, o);
  const double skin = s.neighbor_skin * 2.0 * r_max;
  const ParticleStore& p = sim.particles();
  // No particle twice on a rank.
  std::vector<GlobalId> ids = p.id;
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end());
  long owned = sim.owned(), total = 0;
  MPI_Allreduce(&owned, &total, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(total, static_cast<long>(all.size()));
  long missing = 0, checked = 0;
  for (int i = 0; i < sim.owned(); ++i) {
    EXPECT_EQ(sim.decomposition().owner_of(p.x[i]), sim.decomposition().rank());
    const GlobalId gi = p.id[i];
    std::vector<GlobalId> brute, local;
    for (std::size_t j = 0; j < all.size(); ++j) {
      const double cut = all.radius[gi] + all.radius[j] + skin;
      if (static_cast<GlobalId>(j) != gi && (all.x[j] - all.x[gi]).squaredNorm() < cut * cut)
        brute.push_back(static_cast<GlobalId>(j));
    }
    for (std::size_t j = 0; j < p.size(); ++j) {
      const double cut = p.radius[i] + p.radius[j] + skin;
      if (static_cast<int>(j) != i && (p.x[j] - p.x[i]).squaredNorm() < cut * cut) local.push_back(p.id[j]);
    }
    std::sort(local.begin(), local.end());
    missing += brute == local ? 0 : 1;
    checked += static_cast<long>(brute.size());
  }
  EXPECT_EQ(missing, 0);
  EXPECT_GT(checked, 0);
  if (test::world_size() > 1) {
    EXPECT_GT(p.size(), static_cast<std::size_t>(sim.owned()));
  }
}
