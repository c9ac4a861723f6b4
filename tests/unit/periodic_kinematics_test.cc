// The kinematics of a periodic cell's grains for the strain (upscale/strain/periodic_kinematics.h):
// x* = x + h (n - n0) and u + L x*, with numbers: a grain that crossed a face, one that has not
// since t0, one across a sliding face of a sheared cell, one poured since t0; and an affine
// motion of the cell carries the reference positions to F x*(t0) for a grain in another image at t0.
#include "upscale/strain/periodic_kinematics.h"

#include <algorithm>
#include <random>
#include <sstream>

#include "upscale/strain/cell_deformation.h"

#include <gtest/gtest.h>

#include "dem/core/cell_motion.h"
#include "dem/core/error.h"

namespace upgrain::upscale {
namespace {

dem::PeriodicCell cube() {
  return dem::make_periodic_cell({Vec3(0.0, 0.0, 0.0), Vec3(1.0, 2.0, 4.0)}, {true, true, true});
}

TEST(PeriodicKinematics, GrainsAreFollowedFromTheirImageAtTheReference) {
  const dem::PeriodicCell cell = cube();
  const std::vector<GlobalId> id = {3, 5, 9};
  const std::vector<Vec3> x = {Vec3(0.25, 0.5, 1.0), Vec3(0.75, 1.5, 3.0), Vec3(0.5, 0.5, 0.5)};
  const std::vector<Vec3> u = {Vec3(1.0, 0.0, 0.0), Vec3::Zero(), Vec3(0.0, 0.0, -2.0)};
  const std::vector<ImageCount> image = {{1, 0, 0}, {-2, 1, 3}, {0, 0, -1}};
  // Grain 9 is not in the reference (poured since): followed from its image now.
  const std::vector<GlobalId> ref_id = {1, 3, 5};
  const std::vector<ImageCount> ref_image = {{0, 0, 0}, {0, 0, 0}, {-2, 1, 3}};
  const PeriodicKinematics k = periodic_kinematics(cell, Mat3::Zero(), id, x, u, image, ref_id, ref_image);
  EXPECT_EQ(k.x[0], Vec3(1.25, 0.5, 1.0)) << "crossed the x face once since t0";
  EXPECT_EQ(k.x[1], x[1]) << "in the image it was in at t0";
  EXPECT_EQ(k.x[2], x[2]) << "poured since t0";
  for (int i = 0; i < 3; ++i) EXPECT_EQ(k.v[i], u[i]) << "a fixed cell: the velocities as they are";
}

TEST(PeriodicKinematics, SlidingImagesAndTheMeanFlow) {
  // Shear along x across z with the tilt h_xz = 0.3 (turns 1 of L_x = 1 and offset -0.7).
  dem::PeriodicCell cell = cube();
  cell.shear = dem::ShearImages{0, 2, -0.7, 1};
  ASSERT_DOUBLE_EQ(cell.tilt(), 0.3);
  Mat3 l = Mat3::Zero();
  l(0, 2) = 2.0;
  l(2, 2) = -0.5;
  const std::vector<GlobalId> id = {7};
  const std::vector<Vec3> x = {Vec3(0.5, 1.0, 0.25)}, u = {Vec3(0.1, 0.2, 0.3)};
  const std::vector<ImageCount> image = {{2, 0, 1}}, ref_image = {{1, 0, 0}};
  const PeriodicKinematics k = periodic_kinematics(cell, l, id, x, u, image, id, ref_image);
  // x + h (1, 0, 1): + L_x along x, + L_z along z, + the tilt along x.
  const Vec3 expected(0.5 + 1.0 + 0.3, 1.0, 0.25 + 4.0);
  EXPECT_NEAR((k.x[0] - expected).norm(), 0.0, 1e-15);
  EXPECT_NEAR((k.v[0] - (u[0] + l * expected)).norm(), 0.0, 1e-14);
}

TEST(PeriodicKinematics, AnAffineMotionCarriesEveryImageAlong) {
  // A grain at X in image n0 at t0 (x*(t0) = X); the cell moves by F, h(t) = F h(t0), and the
  // grain with it to the unwrapped point F (X + h0 n0), wrapped into image n. Then x*(t) = F X.
  const dem::PeriodicCell c0 = cube();
  Mat3 f = Mat3::Identity();
  f(0, 0) = 1.25;
  f(2, 2) = 0.8;
  f(0, 2) = 0.15;  // the tilt h_xz = 0.15 * 4 = 0.6
  dem::PeriodicCell c1 =
      dem::make_periodic_cell({Vec3(0.0, 0.0, 0.0), Vec3(1.25, 2.0, 3.2)}, {true, true, true});
  c1.shear = dem::ShearImages{0, 2, 0.6, 0};
  const Mat3 h0 = dem::cell_matrix(c0), h1 = dem::cell_matrix(c1);
  ASSERT_NEAR((h1 - f * h0).norm(), 0.0, 1e-15);
  const Vec3 X(0.3, 1.1, 3.9);
  const ImageCount n0 = {-1, 2, 1};
  const Vec3 unwrapped_now = f * (X + h0 * Vec3(-1.0, 2.0, 1.0));
  // Its wrapped position in the image n = (0, 2, 2) of the moved cell.
  const ImageCount n = {0, 2, 2};
  const Vec3 x = unwrapped_now - h1 * Vec3(0.0, 2.0, 2.0);
  const std::vector<GlobalId> id = {1};
  const PeriodicKinematics k =
      periodic_kinematics(c1, Mat3::Zero(), id, std::vector<Vec3>{x}, std::vector<Vec3>{Vec3::Zero()},
                          std::vector<ImageCount>{n}, id, std::vector<ImageCount>{n0});
  EXPECT_NEAR((k.x[0] - f * X).norm(), 0.0, 1e-14);
}

TEST(PeriodicKinematics, SpansOfOtherLengthsAreRefused) {
  const std::vector<GlobalId> id = {1, 2};
  const std::vector<Vec3> x = {Vec3::Zero()};
  const std::vector<ImageCount> image = {{0, 0, 0}, {0, 0, 0}};
  EXPECT_THROW(static_cast<void>(periodic_kinematics(cube(), Mat3::Zero(), id, x, x, image, id, image)),
               Error);
}

// The cell's F beside the grains' (cell_deformation.h): grains on the affine field of the cell
// give the cell's F to round-off; a grain in one of the two states only is left out; along a
// bounded axis the components do not count; the table's rows have the header's columns.
TEST(CellDeformation, GrainsOnTheCellsAffineFieldGiveTheCellsF) {
  Mat3 h0 = Mat3::Zero();
  h0.diagonal() = Vec3(0.02, 0.03, 0.025);
  Mat3 f = Mat3::Identity();
  f(0, 0) = 0.9;
  f(2, 2) = 1.1;
  f(0, 2) = 0.7;
  const Mat3 h = f * h0;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<GlobalId> ref_id, id;
  std::vector<Vec3> ref_x, x;
  for (GlobalId k = 0; k < 40; ++k) {
    const Vec3 a(0.02 * u(rng), 0.03 * u(rng), 0.025 * u(rng));
    if (k != 7) ref_id.push_back(k), ref_x.push_back(a);                      // 7: poured since t0
    if (k != 11) id.push_back(k), x.push_back(f * a + Vec3(1e-3, 0.0, 0.0));  // 11: gone since
  }
  const CellDeformation d = cell_deformation(h0, h, {true, true, true}, ref_id, ref_x, id, x);
  ASSERT_TRUE(d.grains.valid);
  EXPECT_EQ(d.grains.points, 38);
  EXPECT_NEAR((d.cell - f).cwiseAbs().maxCoeff(), 0.0, 1e-15);
  EXPECT_LE(d.difference, 1e-14);
  // A floor along z: the grains settle (F_zz 0.95) where the cell does not move; not counted.
  for (Vec3& p : x) p.z() *= 0.95 / 1.1;
  const CellDeformation bed = cell_deformation(h0, h, {true, true, false}, ref_id, ref_x, id, x);
  EXPECT_LE(bed.difference, 1e-14);
  EXPECT_GT(cell_deformation(h0, h, {true, true, true}, ref_id, ref_x, id, x).difference, 0.1);
  std::istringstream header(cell_deformation_header());
  std::string line, columns;
  while (std::getline(header, line))
    if (!line.starts_with("#")) columns = line;
  const std::string row = cell_deformation_row(0.5, 100, d);
  EXPECT_EQ(std::count(columns.begin(), columns.end(), ','), std::count(row.begin(), row.end(), ','));
}

}  // namespace
}  // namespace upgrain::upscale
