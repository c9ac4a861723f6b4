// Rank-independent results: the same scene on K ranks and on one rank gives the same
// particle states bit for bit (docs/parallel.md), and one rank agrees with the fast
// summation to round-off (its force sum runs in another order).
#include <gtest/gtest.h>
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "dem/engine/simulation.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

TEST(Determinism, PatchTestOf162SpheresIsBitwiseIdentical) {
  const SceneConfig s = test::patch_scene();
  const ParticleStore p = fill_container(s);
  ASSERT_EQ(p.size(), 162u);
  const RankDiagnostics d = test::expect_rank_independent(s, p, make_open_box(s.container), {}, {}, 300);
  if (test::world_rank() == 0)
    std::printf("patch test on %d ranks: %ld rebuilds\n", test::world_size(), d.rebuilds);
}

TEST(Determinism, DepositionOf600SpheresIsBitwiseIdentical) {
  const SceneConfig s = test::deposition_scene(600);
  const ParticleStore p = fill_container(s);
  const RankDiagnostics d = test::expect_rank_independent(s, p, make_open_box(s.container), {}, {}, 3000);
  long migrated = 0;
  MPI_Allreduce(&d.migrated_out, &migrated, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  if (test::world_rank() == 0)
    std::printf("deposition: %ld rebuilds, %ld migrations\n", d.rebuilds, migrated);
  if (test::world_size() > 1) {
    EXPECT_GT(migrated, 0);
  }
}

namespace {
double max_abs_diff(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double& scale) {
  double diff = 0.0;
  scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, (a[i] - b[i]).cwiseAbs().maxCoeff());
    scale = std::max(scale, a[i].cwiseAbs().maxCoeff());
  }
  return diff;
}
ParticleStore sorted_by_id(const ParticleStore& p) {
  std::vector<int> perm(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) perm[p.id[i]] = static_cast<int>(i);
  ParticleStore q = p;
  q.permute(perm);
  return q;
}
}  // namespace

// One rank against the fast summation: the same integrator and contact law, the force sum
// in another order, so equal to round-off rather than bitwise. Also reports the cost of
// the deterministic sum.
TEST(Determinism, OneRankMatchesTheFastSummation) {
  if (test::world_rank() != 0) return;
  const SceneConfig s = test::patch_scene();
  const ParticleStore p = fill_container(s);
  Simulation fast(s, p, MPI_COMM_SELF, test::fast_summation());
  Simulation one(s, p, MPI_COMM_SELF);
  fast.run(300);
  one.run(300);
  const ParticleStore a = sorted_by_id(fast.particles());
  const ParticleStore b = one.gather_sorted_by_id();
  double scale = 0.0;
  EXPECT_LE(max_abs_diff(a.x, b.x, scale), 1e-12 * scale);
  EXPECT_LE(max_abs_diff(a.v, b.v, scale), 1e-12 * scale);
  EXPECT_LE(max_abs_diff(a.omega, b.omega, scale), 1e-12 * scale);
}

TEST(Determinism, CostAgainstTheFastSummation) {
  if (test::world_rank() != 0) return;
  const SceneConfig s = test::deposition_scene(600);
  const ParticleStore p = fill_container(s);
  Simulation fast(s, p, MPI_COMM_SELF, test::fast_summation());
  Simulation one(s, p, MPI_COMM_SELF);
  fast.run(300);  // warm-up, and past the first impacts
  one.run(300);
  using Clock = std::chrono::steady_clock;
  const long steps = 1500;
  const auto t0 = Clock::now();
  fast.run(steps);
  const auto t1 = Clock::now();
  one.run(steps);
  const auto t2 = Clock::now();
  const double ts = std::chrono::duration<double>(t1 - t0).count();
  const double tp = std::chrono::duration<double>(t2 - t1).count();
  std::printf(
      "cost: fast summation %.3g s, deterministic %.3g s, ratio %.3f (%ld steps, %zu "
      "spheres)\n",
      ts, tp, tp / ts, steps, p.size());
}
