// The coarse-grained fields in parallel (docs/coarse-graining.md, "In parallel"): each rank
// evaluates its own points from the part of rank 0's state near them, and the fields are the
// same bits as rank 0's over the whole state, on 1, 2 and 3 ranks (this binary runs plain and
// under mpiexec). And from a real DEM state on any number of DEM ranks: the recorded contacts
// reproduce every grain's force, so the balance holds to round-off in mid-deposition.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstring>

#include "../common/relaxed_bed.h"
#include "cg_helpers.h"
#include "dem/engine/simulation.h"
#include "dem/parallel/exchange.h"
#include "upscale/cg/coarse_grained_fields.h"
#include "upscale/cg/periodic_images.h"
#include "upscale/cg/state_distribution.h"

namespace upgrain::upscale::cg {
namespace {

TEST(StateDistribution, PackAndUnpackGiveTheSameState) {
  GrainState s = test::random_state(3, 50);
  s.with_displacement = true;
  s.displacement.assign(s.grains(), Vec3(1, 2, 3));
  const GrainState t = unpack(pack(s));
  EXPECT_EQ(t.id, s.id);
  EXPECT_EQ(t.x, s.x);
  EXPECT_EQ(t.acceleration, s.acceleration);
  EXPECT_EQ(t.displacement, s.displacement);
  EXPECT_EQ(t.branch_force, s.branch_force);
  EXPECT_EQ(t.wall_point, s.wall_point);
  EXPECT_EQ(t.longest_branch, s.longest_branch);
  EXPECT_EQ(t.gravity, s.gravity);
  EXPECT_TRUE(t.with_displacement);
}

// What one point's fields are, flattened, for a bitwise comparison.
struct PointRecord {
  long index;
  double values[1 + 1 + 3 + 9 + 9 + 3 + 3 + 3];
};

PointRecord record(const CoarseGrainedFields& f, std::size_t q, long index) {
  PointRecord r{index, {}};
  double* v = r.values;
  *v++ = f.density[q];
  *v++ = f.volume_fraction[q];
  for (int d = 0; d < 3; ++d) *v++ = f.velocity[q][d];
  for (int e = 0; e < 9; ++e) *v++ = f.stress[q](e / 3, e % 3);
  for (int e = 0; e < 9; ++e) *v++ = f.contact_stress[q](e / 3, e % 3);
  for (int d = 0; d < 3; ++d) *v++ = f.wall_force_density[q][d];
  for (int d = 0; d < 3; ++d) *v++ = f.residual[q][d];
  for (int d = 0; d < 3; ++d) *v++ = f.displacement[q][d];
  return r;
}

template <class K>
class DistributionTest : public ::testing::Test {};
using Kernels = ::testing::Types<GaussianKernel, LucyKernel>;
TYPED_TEST_SUITE(DistributionTest, Kernels);

// Rank r takes the points of the r-th slab in y (as a mesh partition would: a region), its part
// of `whole` through state_for_points, and evaluates them: the same bits as `reference` (the
// whole state as rank 0 sums it) at every point, and more than `nonzero` points with a density.
template <class K>
void expect_same_bits_on_every_rank(const GrainState& whole, const GrainState& reference, const K& kernel,
                                    const std::vector<Vec3>& points, int nonzero_at_least) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<Vec3> mine;
  std::vector<long> index;
  for (std::size_t q = 0; q < points.size(); ++q) {
    const int owner = std::clamp(static_cast<int>((points[q].y() / 0.02 + 0.1) / 1.2 * size), 0, size - 1);
    if (owner == rank) {
      mine.push_back(points[q]);
      index.push_back(static_cast<long>(q));
    }
  }
  const GrainState part =
      state_for_points(rank == 0 ? whole : GrainState{}, mine, kernel.cutoff(), MPI_COMM_WORLD);
  if (size > 1) {
    EXPECT_LT(part.grains(), reference.grains());
  }
  EXPECT_FALSE(part.cell.any());
  const CoarseGrainedFields f = coarse_grain(part, mine, kernel);
  std::vector<PointRecord> records;
  for (std::size_t q = 0; q < mine.size(); ++q) records.push_back(record(f, q, index[q]));
  const std::vector<PointRecord> all = dem::gather_to_root(records, MPI_COMM_WORLD);
  if (rank != 0) return;
  ASSERT_EQ(all.size(), points.size());
  const CoarseGrainedFields expected_fields = coarse_grain(reference, points, kernel);
  int nonzero = 0;
  for (const PointRecord& r : all) {
    const PointRecord expected = record(expected_fields, static_cast<std::size_t>(r.index), r.index);
    EXPECT_EQ(std::memcmp(r.values, expected.values, sizeof(r.values)), 0) << "point " << r.index;
    if (expected.values[0] != 0.0) ++nonzero;
  }
  EXPECT_GT(nonzero, nonzero_at_least);
}

TYPED_TEST(DistributionTest, FieldsAreTheSameBitsOnAnyNumberOfRanks) {
  GrainState whole = test::random_state(17, 400);
  whole.with_displacement = true;
  for (std::size_t i = 0; i < whole.grains(); ++i) whole.displacement.push_back(1e-3 * whole.v[i]);
  expect_same_bits_on_every_rank(whole, whole, TypeParam(1.5e-3), test::random_points(18, 3000), 2000);
}

// The same state in a cell periodic along x and y (docs/coarse-graining.md, "Periodic cells"):
// rank 0 adds the images once, in the whole state's order, before it cuts the parts, so every
// rank's fields are the bits of the imaged whole state; and the images change the fields near
// the faces.
TYPED_TEST(DistributionTest, PeriodicFieldsAreTheSameBitsOnAnyNumberOfRanks) {
  GrainState whole = test::random_state(17, 400);
  whole.with_displacement = true;
  for (std::size_t i = 0; i < whole.grains(); ++i) whole.displacement.push_back(1e-3 * whole.v[i]);
  dem::Box box;
  box.hi = Vec3(0.02, 0.02, 0.012);
  whole.cell = dem::make_periodic_cell(box, {true, true, false});
  const TypeParam kernel(1.5e-3);
  const GrainState imaged = with_periodic_images(whole, kernel.cutoff());
  ASSERT_GT(imaged.grains(), whole.grains());
  ASSERT_GT(imaged.branches(), whole.branches());
  const std::vector<Vec3> points = test::random_points(18, 3000);
  expect_same_bits_on_every_rank(whole, imaged, kernel, points, 2000);
  const Vec3 on_face(0.0, 0.01, 0.003);
  EXPECT_GT(coarse_grain(imaged, std::vector{on_face}, kernel).density[0],
            1.2 * coarse_grain(whole, std::vector{on_face}, kernel).density[0]);
}

// 200 grains falling into a box, mid-deposition (colliding, spinning), on every rank of the
// world: the gathered state's recorded contacts (pairs and walls) reproduce each grain's
// force, so with the engine's accelerations the balance holds to round-off, while the bed is
// far from rest (d(rho v)/dt of the order of rho g).
TEST(EngineState, MomentumBalanceAtRoundOffMidDeposition) {
  const dem::SceneConfig scene = upgrain::test::paper_bed_scene(200);
  dem::Simulation sim(scene, dem::fill_container(scene), MPI_COMM_WORLD);
  sim.run(3000);
  sim.request_contacts();
  sim.step();
  const dem::ParticleStore& all = sim.whole_state();
  const std::vector<dem::ContactRecord> contacts = sim.gather_contacts_by_id();
  if (!sim.is_root()) return;
  const GrainState s = state_from(all, contacts, sim.gravity(), sim.time());
  ASSERT_GT(s.wall_contacts(), 10u);
  ASSERT_GT(s.branches(), 2 * s.wall_contacts() + 100);
  std::vector<Vec3> points;
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i)
        points.emplace_back((i + 0.5) / 12 * scene.container.lx, (j + 0.5) / 12 * scene.container.ly,
                            (k + 0.5) * 1e-3);
  for (double w : {0.5, 1.0, 2.0}) {
    const CoarseGrainedFields f = coarse_grain(s, points, GaussianKernel(w * 3e-3));
    double weight = 0, rate = 0, worst = 0;
    for (std::size_t q = 0; q < points.size(); ++q) {
      weight = std::max(weight, (f.density[q] * s.gravity).norm());
      rate = std::max(rate, f.momentum_rate[q].norm());
      worst = std::max(worst, f.residual[q].norm());
    }
    EXPECT_GT(rate, 0.1 * weight);
    EXPECT_LE(worst, 1e-12 * weight) << w;
    std::printf("  w = %.1f d: |residual| %.2e, |d(rho v)/dt| %.2e of rho g\n", w, worst / weight,
                rate / weight);
  }
}

}  // namespace
}  // namespace upgrain::upscale::cg
