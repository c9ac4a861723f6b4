// The equivalent-continuum (Delaunay) deformation and velocity gradients
// (upscale/strain/equivalent_continuum.h): affine maps of a random packing recovered to
// round-off, at the origin and 2 m away; the tessellated volume of a set that contains
// the corners of a cube is the cube; rigid rotation gives D = 0 and W = the spin; a
// non-affine field gives the volume average of the piecewise-linear gradient; degenerate
// sets are reported, not NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "upscale/strain/deformation_fit.h"
#include "upscale/strain/equivalent_continuum.h"

using namespace upgrain::dem;
using namespace upgrain::upscale;

namespace {

std::vector<Vec3> random_points(int n, const Vec3& lo, double side, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, side);
  std::vector<Vec3> p;
  for (int k = 0; k < n; ++k) p.push_back(lo + Vec3(u(rng), u(rng), u(rng)));
  return p;
}

Mat3 rotation(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).matrix(); }

std::vector<Mat3> affine_maps() {
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 1.0;
  const Mat3 stretch = Vec3(1.5, 1.0, 1.0).asDiagonal();
  const double pi = std::numbers::pi;
  return {stretch,
          shear,
          rotation(Vec3::UnitZ(), pi / 2),
          rotation(Vec3(1, 1, 1), pi),
          rotation(Vec3(1, -2, 0.5), pi) * shear * stretch,
          shear * rotation(Vec3(0, 1, 1), pi / 2) * stretch};
}

}  // namespace

TEST(EquivalentContinuum, RecoversAffineMapsToRoundOffNearAndFarFromTheOrigin) {
  const double side = 0.05;
  const Vec3 shift(0.3, -0.1, 0.2);
  for (const Vec3& lo : {Vec3(0, 0, 0), Vec3(Vec3(2, 2, 2) / std::sqrt(3.0))}) {
    const std::vector<Vec3> ref = random_points(300, lo, side, 3);
    for (const Mat3& f : affine_maps()) {
      std::vector<Vec3> cur;
      for (const Vec3& x : ref) cur.push_back(f * x + shift);
      const TessellationGradient t = equivalent_continuum_deformation(ref, cur);
      ASSERT_TRUE(t.valid) << t.reason;
      EXPECT_LE((t.gradient - f).norm(), 1e-12 * f.norm()) << "offset " << lo.transpose() << "\n"
                                                           << t.gradient;
      EXPECT_GT(t.tetrahedra, 300);
      EXPECT_GT(t.volume, 0.5 * side * side * side);
      EXPECT_LT(t.volume, side * side * side);
    }
  }
}

TEST(EquivalentContinuum, TessellatedVolumeOfACubeWithItsCornersIsTheCube) {
  const double side = 0.02;
  std::vector<Vec3> p = random_points(100, Vec3(1, 1, 1), side, 5);
  for (int c = 0; c < 8; ++c) p.push_back(Vec3(1, 1, 1) + side * Vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
  const TessellationGradient t = equivalent_continuum_deformation(p, p);
  ASSERT_TRUE(t.valid);
  EXPECT_NEAR(t.volume, side * side * side, 1e-12 * side * side * side);
  EXPECT_LE((t.gradient - Mat3::Identity()).norm(), 1e-13);
}

TEST(EquivalentContinuum, RigidRotationVelocityHasNoStretchingAndTheSpin) {
  const std::vector<Vec3> x = random_points(200, Vec3(-1.2, 0.4, 1.9), 0.03, 11);
  const Vec3 w(3.0, -1.0, 2.0), v0(0.1, 0.2, -0.3);
  std::vector<Vec3> v;
  for (const Vec3& p : x) v.push_back(w.cross(p) + v0);
  const TessellationGradient t = equivalent_continuum_velocity_gradient(x, v);
  ASSERT_TRUE(t.valid);
  const Mat3 d = 0.5 * (t.gradient + t.gradient.transpose());
  const Mat3 spin = 0.5 * (t.gradient - t.gradient.transpose());
  Mat3 expected;
  expected << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  EXPECT_LE(d.norm(), 1e-12 * w.norm());
  EXPECT_LE((spin - expected).norm(), 1e-12 * w.norm());
}

TEST(EquivalentContinuum, NonAffineMotionDiffersFromTheBestFitButBothSeeTheMeanStretch) {
  // A smooth non-affine field x = X + a sin(k X_1) e_1 on a cell a quarter wavelength
  // long: both definitions give F_11 between the end slopes, and they differ (they are
  // different averages), while the other components stay those of the identity.
  const double side = 0.04, a = 0.002, k = std::numbers::pi / (2 * side);
  const std::vector<Vec3> ref = random_points(400, Vec3::Zero(), side, 17);
  std::vector<Vec3> cur;
  for (const Vec3& p : ref) cur.push_back(p + Vec3(a * std::sin(k * p.x()), 0, 0));
  const TessellationGradient t = equivalent_continuum_deformation(ref, cur);
  const AffineFit fit = fit_deformation_gradient(ref, cur);
  ASSERT_TRUE(t.valid);
  ASSERT_TRUE(fit.valid);
  const double lo = 1.0, hi = 1.0 + a * k;  // slopes of x_1 at X_1 = side and X_1 = 0
  EXPECT_GT(t.gradient(0, 0), lo);
  EXPECT_LT(t.gradient(0, 0), hi);
  EXPECT_GT(fit.gradient(0, 0), lo);
  EXPECT_LT(fit.gradient(0, 0), hi);
  EXPECT_GT(std::abs(t.gradient(0, 0) - fit.gradient(0, 0)), 1e-6);
  EXPECT_NEAR(t.gradient(1, 1), 1.0, 1e-12);
  EXPECT_NEAR(t.gradient(2, 2), 1.0, 1e-12);
}

TEST(EquivalentContinuum, DegenerateSetsAreReportedNotNaN) {
  const std::vector<Vec3> three = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  TessellationGradient t = equivalent_continuum_deformation(three, three);
  EXPECT_FALSE(t.valid);
  EXPECT_NE(t.reason.find("fewer than 4"), std::string::npos);
  std::vector<Vec3> flat = random_points(50, Vec3::Zero(), 1.0, 2);
  for (Vec3& p : flat) p.z() = 0.5;
  t = equivalent_continuum_deformation(flat, flat);
  EXPECT_FALSE(t.valid);
  EXPECT_NE(t.reason.find("coplanar"), std::string::npos);
  EXPECT_TRUE(t.gradient.allFinite());
  // Flat only to round-off: CGAL would tessellate it into slivers.
  std::vector<Vec3> nearly = random_points(50, Vec3(2, 2, 2), 0.05, 6);
  for (Vec3& p : nearly) p.z() = 2.0 + 1e-14 * p.x();
  t = equivalent_continuum_deformation(nearly, nearly);
  EXPECT_FALSE(t.valid);
  EXPECT_NE(t.reason.find("coplanar"), std::string::npos);
  std::vector<Vec3> bad = random_points(10, Vec3::Zero(), 1.0, 4);
  bad[3].x() = std::nan("");
  t = equivalent_continuum_deformation(bad, bad);
  EXPECT_FALSE(t.valid);
  EXPECT_TRUE(t.gradient.allFinite());
}

// L over the reference tetrahedra carried to the current positions: exact for an affine
// velocity field whatever the (non-inverting) deformation since t0, 2 m from the origin; the
// volume is that of the deformed tessellation (det F times the reference one); a motion that
// turns one tetrahedron inside out is refused with the reason, and a new tessellation of the
// current positions then gives L again.
TEST(EquivalentContinuum, CarriedTetrahedraGiveLWhileNoneHasInverted) {
  const Vec3 lo = Vec3(2, 2, 2) / std::sqrt(3.0);
  const std::vector<Vec3> ref = random_points(200, lo, 0.05, 5);
  const DelaunayTetrahedra t = delaunay_tetrahedra(ref);
  ASSERT_TRUE(t.valid);
  const double ref_volume = gradient_over_tetrahedra(t, ref, ref).volume;
  Mat3 velocity_gradient;
  velocity_gradient << 0.3, -1.2, 0.4, 0.7, -0.1, 0.2, -0.5, 0.9, 0.25;
  for (const Mat3& f : affine_maps()) {
    std::vector<Vec3> x, v;
    for (const Vec3& p : ref) {
      x.push_back(f * p + Vec3(0.01, 0.02, -0.03));
      v.push_back(velocity_gradient * x.back() + Vec3(1.0, -2.0, 0.5));
    }
    const TessellationGradient l = gradient_over_carried_tetrahedra(t, x, v);
    ASSERT_TRUE(l.valid) << l.reason;
    EXPECT_LE((l.gradient - velocity_gradient).norm(), 1e-11 * velocity_gradient.norm()) << l.gradient;
    EXPECT_NEAR(l.volume, f.determinant() * ref_volume, 1e-12 * ref_volume);
  }
  // Push one vertex of the first tetrahedron through its opposite face.
  std::vector<Vec3> x = ref, v(ref.size(), Vec3::Zero());
  const std::array<int, 4>& tet = t.tetrahedra.front();
  const Vec3 face = (ref[tet[1]] + ref[tet[2]] + ref[tet[3]]) / 3.0;
  x[tet[0]] = face + 0.5 * (face - ref[tet[0]]);
  const TessellationGradient inverted = gradient_over_carried_tetrahedra(t, x, v);
  EXPECT_FALSE(inverted.valid);
  EXPECT_EQ(inverted.reason, "a tetrahedron has inverted");
  EXPECT_TRUE(gradient_over_tetrahedra(delaunay_tetrahedra(x), x, v).valid);
}
