// Coarse-grained fields in a periodic cell (docs/coarse-graining.md, "Periodic cells"): a pair
// of touching grains across a face, a corner and the sliding face of a sheared cell gives the
// fields of the same pair inside the cell at the points related by the same shift, wherever
// its contact point was recorded; a uniform periodic lattice has the same density and volume
// fraction on the faces, edges and corners as at the centre.
#include <gtest/gtest.h>

#include <random>

#include "../common/periodic_pairs.h"
#include "cg_helpers.h"
#include "upscale/cg/coarse_grained_fields.h"
#include "upscale/cg/periodic_images.h"

namespace upgrain::upscale::cg {
namespace {

double largest_norm(const std::vector<Mat3>& m) {
  double s = 0.0;
  for (const Mat3& t : m) s = std::max(s, t.cwiseAbs().maxCoeff());
  return s;
}

// The state of spheres 0 at xa and 1 at xb (radius 1.5 mm) touching at `point` with force f on
// 0, through state_from in `cell`, its images added for a kernel of cut-off `reach`.
GrainState pair_state(const dem::PeriodicCell& cell, const Vec3& xa, const Vec3& xb, const Vec3& point,
                      const Vec3& f, double reach) {
  dem::ParticleStore p;
  p.add_sphere(0, 1.5e-3, 2650, xa, Vec3(0.1, 0, 0), Vec3::Zero());
  p.add_sphere(1, 1.5e-3, 2650, xb, Vec3(0, -0.2, 0), Vec3::Zero());
  p.force = {f, -f};
  dem::ContactRecord c{0, 1, {}, {}};
  dem::put(c.point, point);
  dem::put(c.force, f);
  return with_periodic_images(state_from(p, {c}, Vec3(0, 0, -9.81), 0.0, nullptr, &cell), reach);
}

TEST(PeriodicFields, PairAcrossAFaceACornerAndASlidingFaceIsThePairInsideTheCell) {
  const GaussianKernel kernel(1e-3);
  const Vec3 f(-2e-3, 1e-4, 3e-4);
  for (const upgrain::test::PeriodicPair& c : upgrain::test::periodic_pairs()) {
    // The contact point of spheres: on the line of centres, half the overlap short of a's radius.
    const double overlap = 3e-3 - c.d.norm();
    ASSERT_GT(overlap, 0.0) << c.name;
    const Vec3 to_point = (1.5e-3 - 0.5 * overlap) * c.d.normalized();
    const GrainState inside =
        pair_state(c.cell, c.inside_a, c.inside_a + c.d, c.inside_a + to_point, f, kernel.cutoff());
    ASSERT_EQ(inside.grains(), 2u) << "the pair inside is out of the images' reach";
    ASSERT_EQ(inside.branches(), 1u);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> at_inside, at_across;
    for (int k = 0; k < 400; ++k) {
      const Vec3 r = c.inside_a + 0.5 * c.d + 3e-3 * Vec3(u(rng), u(rng), u(rng));
      at_inside.push_back(r);
      at_across.push_back(upgrain::test::in_cell(c.cell, r, c.translation));
    }
    const CoarseGrainedFields expected = coarse_grain(inside, at_inside, kernel);
    const double stress = largest_norm(expected.contact_stress);
    const double density = *std::max_element(expected.density.begin(), expected.density.end());
    ASSERT_GT(stress, 0.0);
    // The contact point as the engine may record it: next to a, or next to b's wrapped centre.
    for (const Vec3& point : {Vec3(c.xa + to_point), Vec3(c.xb + to_point - c.d)}) {
      SCOPED_TRACE(c.name);
      const GrainState across = pair_state(c.cell, c.xa, c.xb, point, f, kernel.cutoff());
      EXPECT_FALSE(across.cell.any());
      EXPECT_LE(across.longest_branch, c.d.norm() * (1 + 1e-12)) << "a branch across the cell";
      const CoarseGrainedFields got = coarse_grain(across, at_across, kernel);
      double worst_stress = 0.0, worst_density = 0.0, worst_balance = 0.0;
      for (std::size_t q = 0; q < at_inside.size(); ++q) {
        worst_stress = std::max(worst_stress,
                                (got.contact_stress[q] - expected.contact_stress[q]).cwiseAbs().maxCoeff());
        worst_density = std::max(worst_density, std::abs(got.density[q] - expected.density[q]));
        worst_balance =
            std::max(worst_balance, (got.net_force_density[q] - expected.net_force_density[q]).norm());
      }
      EXPECT_LE(worst_stress, 1e-10 * stress);
      EXPECT_LE(worst_density, 1e-10 * density);
      EXPECT_LE(worst_balance, 1e-10 * largest_norm(expected.contact_stress) / kernel.cutoff());
    }
  }
}

// A grain's displacement across a face follows its image counter (x + h (n - n0) - X), also
// beyond half a cell length; a reference without counters (an older checkpoint) takes the
// minimum image, which folds that one.
TEST(PeriodicFields, DisplacementFollowsTheGrainAcrossTheFaces) {
  const dem::PeriodicCell cell = upgrain::test::periodic_cube(0.02);
  dem::ParticleStore p;
  p.add_sphere(0, 1e-3, 2650, Vec3(0.0195, 0.01, 0.01), Vec3::Zero(), Vec3::Zero());
  p.add_sphere(1, 1e-3, 2650, Vec3(0.0195, 0.005, 0.01), Vec3::Zero(), Vec3::Zero());
  for (Vec3& x : p.x) dem::snap(cell, x);
  const ReferencePositions ref = reference_from(p, 0.0, &cell);
  ASSERT_EQ(ref.image.size(), 2u);
  // Grain 0 moves 0.8 mm through the face x = L, grain 1 moves 14 mm (0.7 L) through it.
  p.x[0] = Vec3(0.0003, 0.01, 0.01);
  p.x[1] = Vec3(0.0135, 0.005, 0.01);
  for (Vec3& x : p.x) dem::snap(cell, x);
  p.image = {{1, 0, 0}, {1, 0, 0}};
  const GrainState s = state_from(p, {}, Vec3::Zero(), 1.0, &ref, &cell);
  EXPECT_NEAR(s.displacement[0].x(), 0.8e-3, 1e-15);
  EXPECT_NEAR(s.displacement[1].x(), 14e-3, 1e-15);
  ReferencePositions without_counters = ref;
  without_counters.image.clear();
  const GrainState folded = state_from(p, {}, Vec3::Zero(), 1.0, &without_counters, &cell);
  EXPECT_NEAR(folded.displacement[0].x(), 0.8e-3, 1e-15);
  EXPECT_NEAR(folded.displacement[1].x(), -6e-3, 1e-15);
  // A bounded box: x - X as it is.
  EXPECT_EQ(state_from(p, {}, Vec3::Zero(), 1.0, &ref).displacement[1], p.x[1] - ref.x[1]);
}

// The images' lattice vectors: the 26 neighbours of a fully periodic cell for a reach below half
// its length, 8 with two periodic axes, more for a longer reach or a sheared cell.
TEST(PeriodicFields, ImageShiftsAreTheNeighbouringCells) {
  dem::PeriodicCell cell = upgrain::test::periodic_cube(0.02);
  EXPECT_EQ(image_shifts(cell, 0.006).size(), 26u);
  EXPECT_EQ(image_shifts(cell, 0.03).size(), 124u);  // two cells along each axis: 5^3 - 1
  cell.shear = {0, 2, 0.003, 0};
  EXPECT_EQ(image_shifts(cell, 0.006).size(), 44u);  // 5 x 3 x 3 - 1: the slid images
  cell = dem::make_periodic_cell(cell.box, {true, true, false});
  EXPECT_EQ(image_shifts(cell, 0.006).size(), 8u);
}

// A simple cubic lattice of 10 x 10 x 10 grains filling a periodic cube: the density and volume
// fraction at the centre, on a face, an edge and a corner (the same place relative to the
// lattice) agree to round-off; without the images the corner sees an eighth of it.
template <class K>
class PeriodicLattice : public ::testing::Test {};
using Kernels = ::testing::Types<GaussianKernel, LucyKernel>;
TYPED_TEST_SUITE(PeriodicLattice, Kernels);

TYPED_TEST(PeriodicLattice, DensityOnTheFacesIsTheDensityAtTheCentre) {
  const double l = 0.02, pitch = l / 10;
  GrainState s;
  s.cell = upgrain::test::periodic_cube(l);
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        Vec3 x = (Vec3(i, j, k) + Vec3::Constant(0.5)) * pitch;
        dem::snap(s.cell, x);
        test::add_grain(s, static_cast<GlobalId>(s.grains()), x, 1e-5, 3e-9);
      }
  const TypeParam kernel(1.2 * pitch);
  const GrainState imaged = with_periodic_images(s, kernel.cutoff());
  const double c = 0.5 * l, e = 0.0;
  const std::vector<Vec3> points = {Vec3(c, c, c),
                                    Vec3(e, c, c),
                                    Vec3(c, e, c),
                                    Vec3(c, c, e),
                                    Vec3(e, e, c),
                                    Vec3(e, e, e),
                                    Vec3(l - 0.25 * pitch, c, c),
                                    Vec3(c - 0.25 * pitch, c, c)};
  const CoarseGrainedFields f = coarse_grain(imaged, points, kernel);
  ASSERT_GT(f.density[0], 0.0);
  for (std::size_t q = 1; q < 6; ++q) {
    EXPECT_NEAR(f.density[q], f.density[0], 1e-12 * f.density[0]) << q;
    EXPECT_NEAR(f.volume_fraction[q], f.volume_fraction[0], 1e-12 * f.volume_fraction[0]) << q;
  }
  // A quarter pitch inside the upper x face is a quarter pitch short of the centre's plane.
  EXPECT_NEAR(f.density[6], f.density[7], 1e-12 * f.density[0]);
  EXPECT_LT(coarse_grain(s, std::vector{points[5]}, kernel).density[0], 0.2 * f.density[0]);
}

}  // namespace
}  // namespace upgrain::upscale::cg
