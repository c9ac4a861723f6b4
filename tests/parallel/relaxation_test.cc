// FIRE on several ranks (dem/engine/relaxation.h): the relaxed state and the
// energy it removes are bitwise the same on any rank count, and the relaxation works (the
// residual falls by orders of magnitude), like the fast summation's.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>

#include "dem/engine/relaxation.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

struct Relaxed {
  ParticleStore state;  // rank 0
  RelaxationResult before, after;
  EnergyBalance energy_before, energy;
};

Relaxed deposit_and_relax(const SceneConfig& s, const ParticleStore& p, MPI_Comm comm, long steps,
                          const RelaxationOptions& o) {
  Simulation sim(s, p, comm);
  sim.run(steps);
  Relaxed r;
  r.before = equilibrium_residual(sim);
  r.energy_before = sim.energy();
  r.after = relax_to_equilibrium(sim, o);
  r.energy = sim.energy();
  r.state = sim.gather_sorted_by_id();
  return r;
}

}  // namespace

TEST(ParallelRelaxation, RelaxedStateAndRemovedEnergyAreBitwiseRankIndependent) {
  const SceneConfig s = test::deposition_scene(600);
  const ParticleStore p = fill_container(s);
  RelaxationOptions o;
  o.max_steps = 3000;
  const Relaxed world = deposit_and_relax(s, p, MPI_COMM_WORLD, 3000, o);
  // Every rank received the same global numbers.
  double mine[3] = {world.after.kinetic_removed, world.after.max_force_residual,
                    world.energy.removed_by_relaxation};
  double lo[3], hi[3];
  MPI_Allreduce(mine, lo, 3, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(mine, hi, 3, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(lo[k], hi[k]) << "quantity " << k << " differs between ranks";
  if (test::world_rank() != 0) return;
  const Relaxed self = deposit_and_relax(s, p, MPI_COMM_SELF, 3000, o);
  test::expect_bitwise_equal(world.state, self.state, std::to_string(test::world_size()) + " ranks vs 1");
  EXPECT_EQ(world.after.steps, self.after.steps);
  EXPECT_EQ(world.after.kinetic_removed, self.after.kinetic_removed);
  EXPECT_EQ(world.after.max_force_residual, self.after.max_force_residual);
  EXPECT_EQ(world.after.max_torque_residual, self.after.max_torque_residual);
  EXPECT_EQ(world.energy.removed_by_relaxation, world.after.kinetic_removed);
  // It relaxes a bed still settling after 3,000 steps: the kinetic energy and the largest
  // out-of-balance force fall (convergence to 1e-9 takes tens of thousands of steps; the
  // driver's study does that, tests/end_to_end).
  EXPECT_LT(world.energy.kinetic(), 1e-2 * world.energy_before.kinetic());
  EXPECT_LT(world.after.max_force_residual, 0.5 * world.before.max_force_residual);
  EXPECT_GT(world.after.kinetic_removed, 0.0);
  std::printf(
      "parallel FIRE on %d ranks: residual %.3e -> %.3e, kinetic %.3e -> %.3e J in %ld steps, %.3e J "
      "removed\n",
      test::world_size(), world.before.max_force_residual, world.after.max_force_residual,
      world.energy_before.kinetic(), world.energy.kinetic(), world.after.steps, world.after.kinetic_removed);
}

TEST(ParallelRelaxation, OneRankFollowsTheFastSummationsRelaxation) {
  // The fast summation's FIRE sums in another order (not bitwise): after a few hundred
  // FIRE steps both states agree to round-off growth, and both residuals fall alike.
  if (test::world_rank() != 0) return;
  const SceneConfig s = test::patch_scene();
  const ParticleStore p = fill_container(s);
  RelaxationOptions o;
  o.max_steps = 200;
  const Relaxed mpi = deposit_and_relax(s, p, MPI_COMM_SELF, 300, o);
  Simulation fast(s, p, MPI_COMM_SELF, test::fast_summation());
  fast.run(300);
  const RelaxationResult r = relax_to_equilibrium(fast, o);
  ASSERT_EQ(r.steps, mpi.after.steps);
  const ParticleStore& q = fast.particles();
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const auto k = static_cast<std::size_t>(
        std::lower_bound(mpi.state.id.begin(), mpi.state.id.end(), q.id[i]) - mpi.state.id.begin());
    worst = std::max(worst, (q.x[i] - mpi.state.x[k]).norm());
    scale = std::max(scale, q.radius[i]);
  }
  EXPECT_LT(worst, 1e-9 * scale);
  EXPECT_NEAR(r.kinetic_removed, mpi.after.kinetic_removed, 1e-9 * r.kinetic_removed);
}
