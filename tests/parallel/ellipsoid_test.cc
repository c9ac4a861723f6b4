// Ellipsoids in the MPI engine (docs/parallel.md, "Ellipsoids"): a deposition of the
// Yan and Regueiro's shapes (docs/stress.md) gives the same positions, velocities, angular velocities and
// orientations bit for bit on K ranks as on one, through migrations (shape state and contact memory travel
// with the grains); one rank agrees with the fast summation on one rank to round-off.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>

#include "../common/relaxed_bed.h"
#include "dem/engine/simulation.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// tests/common/relaxed_bed.h's ellipsoid bed of `count` grains in a box of 4 cm (a few
// layers), thrown down so that they hit the floor and each other within a few thousand steps.
SceneConfig ellipsoid_scene(long count) {
  SceneConfig s = test::paper_ellipsoid_bed_scene(count);
  s.container.lx = s.container.ly = 0.04;
  s.fill.velocity = Vec3(0, 0, -1.0);
  s.fill.velocity_jitter = 0.5;
  return s;
}

long migrations(const RankDiagnostics& d) {
  long migrated = 0;
  MPI_Allreduce(&d.migrated_out, &migrated, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return migrated;
}

// Largest |a - b| and largest |a| over the components of two fields.
template <class Get>
void max_diff(std::size_t n, Get get, double& diff, double& scale) {
  diff = scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto [a, b] = get(i);
    for (int d = 0; d < static_cast<int>(a.size()); ++d) {
      diff = std::max(diff, std::abs(a[d] - b[d]));
      scale = std::max(scale, std::abs(a[d]));
    }
  }
}

}  // namespace

TEST(ParallelEllipsoids, DepositionOf200PaperEllipsoidsIsBitwiseIdentical) {
  const SceneConfig s = ellipsoid_scene(200);
  const ParticleStore p = fill_container(s);
  ASSERT_TRUE(p.has_shapes());
  if (test::world_rank() == 0) std::printf("time step %.3g s\n", s.time_step);
  const RankDiagnostics d = test::expect_rank_independent(s, p, make_open_box(s.container), {}, {}, 15000);
  const long migrated = migrations(d);
  if (test::world_rank() == 0)
    std::printf("ellipsoid deposition on %d ranks: %ld rebuilds, %ld migrations\n", test::world_size(),
                d.rebuilds, migrated);
  if (test::world_size() > 1) {
    EXPECT_GT(migrated, 0);
  }
}

// Mostly spheres with a few flat ellipsoids, energy tracking on (the damping torque's
// work): the mixed pairs take the shaped path, sphere pairs the sphere path.
TEST(ParallelEllipsoids, MixedSpheresAndEllipsoidsAreBitwiseIdentical) {
  SceneConfig s = ellipsoid_scene(200);
  s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 3.0), ellipsoid_grain(0.6, 0.4, 1.0)};
  const ParticleStore p = fill_container(s);
  long ellipsoids = 0;
  for (std::size_t i = 0; i < p.size(); ++i) ellipsoids += p.is_ellipsoid(i) ? 1 : 0;
  ASSERT_GT(ellipsoids, 20);
  ASSERT_LT(ellipsoids, 100);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  Simulation world(s, p, walls, MPI_COMM_WORLD);
  world.run(12000);
  const ParticleStore parallel = world.gather_sorted_by_id();
  const EnergyBalance e = world.energy();
  const StepDiagnostics sd = world.diagnostics();
  const long migrated = migrations(world.rank_diagnostics());
  if (test::world_rank() == 0) {
    Simulation self(s, p, walls, MPI_COMM_SELF);
    self.run(12000);
    test::expect_bitwise_equal(parallel, self.gather_sorted_by_id(),
                               std::to_string(test::world_size()) + " ranks vs 1");
    const EnergyBalance e1 = self.energy();
    // Per-particle terms are summed in global-id order: bitwise.
    EXPECT_EQ(e.kinetic_translational, e1.kinetic_translational);
    EXPECT_EQ(e.kinetic_rotational, e1.kinetic_rotational);
    EXPECT_EQ(e.potential, e1.potential);
    EXPECT_EQ(e.elastic_normal, e1.elastic_normal);
    EXPECT_GT(e.dissipated_damping, 0.0);
    EXPECT_GT(sd.contact_solver.calls, 0);
    std::printf("mixed bed on %d ranks: %ld ellipsoids, %ld migrations, %ld contacts, %lld solver calls\n",
                test::world_size(), ellipsoids, migrated, sd.particle_contacts,
                static_cast<long long>(sd.contact_solver.calls));
  }
  if (test::world_size() > 1) {
    EXPECT_GT(migrated, 0);
  }
}

// One rank against the fast summation: the same contact geometry and law (shared code), the
// same rotation splitting; pairs are solved with the lower id as body i and forces summed
// in another order, so equal to round-off rather than bitwise. After 2500 steps (first
// impacts on the floor and between grains) the differences are about 1e-12 of the scale;
// the impacts amplify them about tenfold per 1000 steps (1e-9 after 5000).
TEST(ParallelEllipsoids, OneRankMatchesTheFastSummation) {
  if (test::world_rank() != 0) return;
  const SceneConfig s = ellipsoid_scene(200);
  const ParticleStore p = fill_container(s);
  Simulation fast(s, p, MPI_COMM_SELF, test::fast_summation());
  Simulation one(s, p, MPI_COMM_SELF);
  fast.run(2500);
  one.run(2500);
  const StepDiagnostics sd = fast.diagnostics();
  std::printf("fast after 2500 steps: %ld pair and %ld wall contacts\n", sd.particle_contacts,
              sd.wall_contacts);
  ASSERT_GT(sd.particle_contacts, 0);
  ASSERT_GT(sd.wall_contacts, 0);
  std::vector<int> perm(p.size());
  const ParticleStore& q = fast.particles();
  for (std::size_t i = 0; i < q.size(); ++i) perm[q.id[i]] = static_cast<int>(i);
  ParticleStore a = q;
  a.permute(perm);
  const ParticleStore b = one.gather_sorted_by_id();
  ASSERT_EQ(a.size(), b.size());
  double diff = 0.0, scale = 0.0;
  max_diff(
      a.size(),
      [&](std::size_t i) {
        return std::pair{a.x[i], b.x[i]};
      },
      diff, scale);
  EXPECT_LE(diff, 1e-10 * scale) << "x";
  std::printf("deterministic vs fast: x differs by %.3g of its scale\n", diff / scale);
  max_diff(
      a.size(),
      [&](std::size_t i) {
        return std::pair{a.v[i], b.v[i]};
      },
      diff, scale);
  EXPECT_LE(diff, 1e-10 * scale) << "v";
  std::printf("deterministic vs fast: v differs by %.3g of its scale\n", diff / scale);
  max_diff(
      a.size(),
      [&](std::size_t i) {
        return std::pair{a.omega[i], b.omega[i]};
      },
      diff, scale);
  EXPECT_LE(diff, 1e-10 * scale) << "omega";
  std::printf("deterministic vs fast: omega differs by %.3g of its scale\n", diff / scale);
  max_diff(
      a.size(),
      [&](std::size_t i) {
        return std::pair{a.orientation[i].coeffs(), b.orientation[i].coeffs()};
      },
      diff, scale);
  EXPECT_LE(diff, 1e-10 * scale) << "orientation";
  std::printf("deterministic vs fast: orientation differs by %.3g of its scale\n", diff / scale);
}
