// Kinematics of a grid cell (upscale/strain/, docs/strain.md) against exact answers: best-fit F
// and L of affine motions of a random packing, near the origin and 2 m from it; the strain
// measures and the polar decomposition against closed forms (simple shear, stretches, rigid
// rotations); objective stress rates of stresses that are only carried along, with the order
// of the time differencing measured; invalid cells reported with the reason and no NaN.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "upscale/strain/deformation_fit.h"
#include "upscale/strain/objective_rates.h"
#include "upscale/strain/strain_measures.h"

using namespace upgrain::dem;
using namespace upgrain::upscale;

namespace {

constexpr double kPi = std::numbers::pi;

// For RecordProperty (shown with --gtest_output=xml): the measured accuracies of docs/strain.md.
std::string sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::vector<Vec3> random_packing(int n, const Vec3& lo, double side, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, side);
  std::vector<Vec3> x(n);
  for (Vec3& p : x) p = lo + Vec3(u(rng), u(rng), u(rng));
  return x;
}

Mat3 rotation(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).matrix(); }

Mat3 simple_shear(double gamma) {
  Mat3 f = Mat3::Identity();
  f(0, 1) = gamma;
  return f;
}

Mat3 uniaxial_stretch(double lambda) { return Vec3(lambda, 1.0, 1.0).asDiagonal(); }

// The affine maps of the verification (docs/strain.md, "Verification"): stretch 1.5, simple shear 1,
// rotations of 90 and 180 degrees about several axes, and products of these.
std::vector<Mat3> test_maps() {
  const Vec3 axes[] = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), Vec3(1, 1, 1), Vec3(1, -2, 0.5)};
  std::vector<Mat3> maps = {uniaxial_stretch(1.5), simple_shear(1.0)};
  for (const Vec3& a : axes) {
    maps.push_back(rotation(a, kPi / 2));
    maps.push_back(rotation(a, kPi));
  }
  maps.push_back(rotation(Vec3::UnitZ(), kPi / 2) * uniaxial_stretch(1.5));
  maps.push_back(uniaxial_stretch(1.5) * rotation(Vec3::UnitX(), kPi));
  maps.push_back(simple_shear(1.0) * rotation(Vec3(1, 1, 1), kPi / 2));
  maps.push_back(rotation(Vec3(1, -2, 0.5), kPi) * simple_shear(1.0) * uniaxial_stretch(1.5));
  maps.push_back(rotation(Vec3::UnitY(), kPi / 2) * simple_shear(1.0) *
                 rotation(Vec3::UnitY(), kPi / 2).transpose());
  return maps;
}

bool finite(const StrainMeasures& m) {
  return std::isfinite(m.jacobian) && std::isfinite(m.volumetric_strain) &&
         std::isfinite(m.equivalent_shear_strain) && m.right_cauchy_green.allFinite() &&
         m.left_cauchy_green.allFinite() && m.green_lagrange.allFinite() && m.euler_almansi.allFinite() &&
         m.hencky_right.allFinite() && m.hencky_left.allFinite() && m.polar.rotation.allFinite() &&
         m.polar.right_stretch.allFinite() && m.polar.left_stretch.allFinite() &&
         m.polar.principal_stretches.allFinite();
}

bool finite(const AffineFit& f) {
  return f.gradient.allFinite() && f.translation.allFinite() && f.centroid.allFinite() &&
         std::isfinite(f.spread_ratio) && std::isfinite(f.residual_rms);
}

// Matrix logarithm of a symmetric positive definite matrix by its eigen-decomposition: an
// independent route to ln U = ln C / 2.
Mat3 spd_log(const Mat3& c) {
  const Eigen::SelfAdjointEigenSolver<Mat3> es(c);
  return es.eigenvectors() * es.eigenvalues().array().log().matrix().asDiagonal() *
         es.eigenvectors().transpose();
}

}  // namespace

// ---------------------------------------------------------------- best fit of F and L

TEST(DeformationFit, RecoversAffineMapsOfARandomPackingToRoundOff) {
  const double side = 0.05;  // a 5 cm cell
  const Vec3 c(0.3, -0.1, 0.2);
  for (const Vec3& lo : {Vec3(0.0, 0.0, 0.0), Vec3(Vec3(2.0, 2.0, 2.0) / std::sqrt(3.0))}) {  // 2 m away
    const std::vector<Vec3> ref = random_packing(200, lo, side, 7);
    double worst = 0.0;
    for (const Mat3& f : test_maps()) {
      std::vector<Vec3> cur;
      for (const Vec3& x : ref) cur.push_back(f * x + c);
      const AffineFit fit = fit_deformation_gradient(ref, cur);
      ASSERT_TRUE(fit.valid) << fit.reason;
      const double err = (fit.gradient - f).norm() / f.norm();
      worst = std::max(worst, err);
      EXPECT_LE(err, 1e-12) << "offset " << lo.transpose() << "\n" << f << "\nfit\n" << fit.gradient;
      EXPECT_LE((fit.translation - c).norm(), 1e-12 * (f.norm() * lo.norm() + c.norm() + side));
      EXPECT_LE(fit.residual_rms, 1e-13 * side);
      EXPECT_GT(fit.spread_ratio, 0.5);
    }
    RecordProperty(lo.norm() > 0 ? "worst_relative_error_at_2m" : "worst_relative_error_at_origin",
                   sci(worst));
  }
}

TEST(DeformationFit, NonAffineResidualIsTheRmsOfTheFluctuation) {
  // x = F X + c + d with d orthogonal to the affine fields (sum d = 0, sum d dX^T = 0):
  // the fit is F exactly and the residual is rms(d) (D^2_min = sum |d|^2).
  const Vec3 lo(1.2, -1.4, 0.8);
  const std::vector<Vec3> ref = random_packing(50, lo, 0.05, 3);
  Eigen::MatrixXd a(50, 4), noise(50, 3);
  std::mt19937_64 rng(9);
  std::normal_distribution<double> nd(0.0, 1e-3);
  for (int p = 0; p < 50; ++p) {
    a.row(p) << 1.0, (ref[p] - lo).transpose();
    noise.row(p) << nd(rng), nd(rng), nd(rng);
  }
  const Eigen::MatrixXd d = noise - a * a.householderQr().solve(noise);
  const Mat3 f = rotation(Vec3(1, 1, 0), 0.7) * simple_shear(0.4);
  std::vector<Vec3> cur;
  for (int p = 0; p < 50; ++p) cur.push_back(f * ref[p] + d.row(p).transpose());
  const AffineFit fit = fit_deformation_gradient(ref, cur);
  ASSERT_TRUE(fit.valid) << fit.reason;
  EXPECT_LE((fit.gradient - f).norm(), 1e-11 * f.norm());
  EXPECT_NEAR(fit.residual_rms, std::sqrt(d.squaredNorm() / 50), 1e-12 * fit.residual_rms);
}

TEST(StrainRate, RigidRotationFieldHasNoStretchingAndTheSpinAsW) {
  const Vec3 omega(0.3, -1.2, 2.0), v0(0.1, 0.2, -0.3);
  for (const Vec3& lo : {Vec3(0.0, 0.0, 0.0), Vec3(2.0, 0.0, 0.0)}) {
    const std::vector<Vec3> x = random_packing(200, lo, 0.05, 11);
    std::vector<Vec3> v;
    for (const Vec3& p : x) v.push_back(omega.cross(p) + v0);
    const AffineFit fit = fit_velocity_gradient(x, v);
    ASSERT_TRUE(fit.valid) << fit.reason;
    EXPECT_LE(rate_of_deformation(fit.gradient).norm(), 1e-12 * omega.norm());
    EXPECT_LE((spin(fit.gradient) - cross_matrix(omega)).norm(), 1e-12 * omega.norm());
    EXPECT_LE((fit.translation - v0).norm(), 1e-12 * (omega.norm() * lo.norm() + v0.norm()));
    EXPECT_LE(equivalent_shear_rate(fit.gradient), 1e-12 * omega.norm());
  }
}

TEST(StrainRate, PureStretchingFieldHasNoSpin) {
  Mat3 d;
  d << 0.5, 0.2, -0.1, 0.2, -0.3, 0.05, -0.1, 0.05, 0.1;
  const std::vector<Vec3> x = random_packing(200, Vec3(-2.0, 0.0, 0.0), 0.05, 13);
  std::vector<Vec3> v;
  for (const Vec3& p : x) v.push_back(d * p + Vec3(1.0, 0.0, 0.0));
  const AffineFit fit = fit_velocity_gradient(x, v);
  ASSERT_TRUE(fit.valid) << fit.reason;
  EXPECT_LE(spin(fit.gradient).norm(), 1e-12 * d.norm());
  EXPECT_LE((rate_of_deformation(fit.gradient) - d).norm(), 1e-12 * d.norm());
  // Simple shear flow: engineering shear rate.
  Mat3 l = Mat3::Zero();
  l(0, 1) = 3.0;
  EXPECT_NEAR(equivalent_shear_rate(l), 3.0, 1e-15);
}

// ---------------------------------------------------------------- polar decomposition

TEST(PolarDecomposition, SimpleShearMatchesTheClosedForm) {
  // F = 1 + gamma e1 e2: with k = sqrt(4 + gamma^2), R is a rotation about e3 by -atan(gamma/2),
  // U = [[2, g, 0], [g, 2 + g^2, 0], [0, 0, k]] / k and V = [[2 + g^2, g, 0], [g, 2, 0], [0, 0, k]] / k.
  for (double g : {1e-3, 0.1, 1.0, 3.0, 10.0}) {
    const double k = std::sqrt(4.0 + g * g);
    Mat3 r, u, v;
    r << 2 / k, g / k, 0, -g / k, 2 / k, 0, 0, 0, 1;
    u << 2 / k, g / k, 0, g / k, (2 + g * g) / k, 0, 0, 0, 1;
    v << (2 + g * g) / k, g / k, 0, g / k, 2 / k, 0, 0, 0, 1;
    const PolarDecomposition pd = polar_decomposition(simple_shear(g));
    ASSERT_TRUE(pd.valid) << pd.reason;
    EXPECT_LE((pd.rotation - r).norm(), 1e-14) << "gamma " << g;
    EXPECT_LE((pd.right_stretch - u).norm(), 1e-14 * u.norm()) << "gamma " << g;
    EXPECT_LE((pd.left_stretch - v).norm(), 1e-14 * v.norm()) << "gamma " << g;
  }
}

TEST(PolarDecomposition, PureStretchHasNoRotationAndRotatedStretchRecoversBoth) {
  const Mat3 q0 = rotation(Vec3(1, 2, 3), 0.8);
  const Mat3 u0 = q0 * Vec3(1.5, 0.8, 1.2).asDiagonal() * q0.transpose();  // symmetric positive definite
  for (const Mat3& u : {Mat3(Vec3(1.5, 0.8, 1.2).asDiagonal()), u0}) {
    const PolarDecomposition pd = polar_decomposition(u);
    ASSERT_TRUE(pd.valid) << pd.reason;
    EXPECT_LE((pd.rotation - Mat3::Identity()).norm(), 1e-14);
    EXPECT_LE((pd.right_stretch - u).norm(), 1e-14);
    EXPECT_LE((pd.left_stretch - u).norm(), 1e-14);
    // Large rotations, including half turns, in front: F = Q U, so R = Q, and V = Q U Q^T.
    for (const Mat3& q : {rotation(Vec3::UnitX(), kPi), rotation(Vec3(1, 1, 1), kPi),
                          rotation(Vec3(0, 1, -1), kPi / 2), rotation(Vec3(3, -1, 2), 2.9)}) {
      const PolarDecomposition p2 = polar_decomposition(q * u);
      ASSERT_TRUE(p2.valid) << p2.reason;
      EXPECT_LE((p2.rotation - q).norm(), 1e-14);
      EXPECT_LE((p2.right_stretch - u).norm(), 1e-14);
      EXPECT_LE((p2.left_stretch - q * u * q.transpose()).norm(), 1e-14);
    }
  }
}

TEST(PolarDecomposition, RandomGradientsGiveProperRotationAndPositiveDefiniteStretches) {
  std::mt19937_64 rng(21);
  std::normal_distribution<double> nd;
  double worst = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    Mat3 f;
    for (int e = 0; e < 9; ++e) f(e / 3, e % 3) = nd(rng);
    if (f.determinant() < 0) f.row(0) *= -1.0;
    const PolarDecomposition pd = polar_decomposition(f);
    ASSERT_TRUE(pd.valid) << pd.reason << "\n" << f;  // s3 < 1e-8 s1 has probability ~1e-8
    const Mat3& r = pd.rotation;
    const Mat3& u = pd.right_stretch;
    const Mat3& v = pd.left_stretch;
    const double err = std::max({(r.transpose() * r - Mat3::Identity()).norm(), (r * u - f).norm() / f.norm(),
                                 (v * r - f).norm() / f.norm()});
    worst = std::max(worst, err);
    EXPECT_LE(err, 1e-14);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
    EXPECT_EQ(u, u.transpose());
    EXPECT_EQ(v, v.transpose());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat3>(u).eigenvalues().minCoeff(), 0.0);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat3>(v).eigenvalues().minCoeff(), 0.0);
  }
  RecordProperty("worst_orthogonality_or_reconstruction_error", sci(worst));
}

TEST(PolarDecomposition, NearSingularGradientIsDecomposedAccurately) {
  const Mat3 q1 = rotation(Vec3(1, 0, 1), 1.1), q2 = rotation(Vec3(0, 1, 2), kPi);
  const Mat3 f = q1 * Vec3(2.0, 1.0, 1e-7).asDiagonal() * q2.transpose();  // J = 2e-7
  const StrainMeasures m = strain_measures(f);
  ASSERT_TRUE(m.valid) << m.reason;
  EXPECT_LE((m.polar.rotation - q1 * q2.transpose()).norm(), 1e-14);
  EXPECT_LE((m.polar.rotation * m.polar.right_stretch - f).norm(), 1e-15 * f.norm());
  // Rounding f's entries (|f| ~ 2) moves s3 by up to a few 1e-16: that is the accuracy the
  // input allows, and the SVD attains it (an eigen-decomposition of C would give s3^2 = 1e-14
  // only to about +-1e-15, i.e. s3 to 5 %).
  EXPECT_NEAR(m.polar.principal_stretches(2), 1e-7, 1e-15);
  EXPECT_NEAR(m.jacobian, 2e-7, 2e-15);
  EXPECT_NEAR(m.volumetric_strain, std::log(2e-7), 1e-8);
  EXPECT_NEAR(m.hencky_right.eigenvalues().real().minCoeff(), std::log(1e-7), 1e-8);
}

// ---------------------------------------------------------------- strain measures

TEST(StrainMeasures, RigidRotationsGiveZeroStrain) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> nd;
  std::vector<Mat3> rotations;
  for (const Vec3& a :
       std::vector<Vec3>{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), Vec3(1, 1, 1), Vec3(1, -2, 0.5)}) {
    rotations.push_back(rotation(a, kPi / 2));
    rotations.push_back(rotation(a, kPi));
  }
  for (int k = 0; k < 50; ++k) {
    rotations.push_back(
        Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized().toRotationMatrix());
  }
  double worst = 0.0;
  for (const Mat3& q : rotations) {
    const StrainMeasures m = strain_measures(q);
    ASSERT_TRUE(m.valid) << m.reason;
    const double err =
        std::max({m.green_lagrange.norm(), m.euler_almansi.norm(), m.hencky_right.norm(),
                  m.hencky_left.norm(), std::abs(m.volumetric_strain), m.equivalent_shear_strain});
    worst = std::max(worst, err);
    // The rotation matrices themselves are orthogonal to a few ulps only.
    EXPECT_LE(err, 5e-15) << q;
    EXPECT_NEAR(m.jacobian, 1.0, 5e-15);
    EXPECT_LE((m.polar.rotation - q).norm(), 5e-15);
  }
  RecordProperty("worst_strain_under_rotation", sci(worst));
}

TEST(StrainMeasures, UniaxialStretchMatchesTheClosedForms) {
  const double l = 1.5;
  for (const Mat3& q : {Mat3(Mat3::Identity()), rotation(Vec3(1, -1, 2), 2.0)}) {
    const Mat3 f = q * uniaxial_stretch(l);  // stretch along e1 in the reference, then turn
    const StrainMeasures m = strain_measures(f);
    ASSERT_TRUE(m.valid) << m.reason;
    const Mat3 e1 = Vec3::UnitX() * Vec3::UnitX().transpose();
    EXPECT_LE((m.green_lagrange - 0.5 * (l * l - 1) * e1).norm(), 1e-15);
    EXPECT_LE((m.euler_almansi - 0.5 * (1 - 1 / (l * l)) * q * e1 * q.transpose()).norm(), 1e-15);
    EXPECT_LE((m.hencky_right - std::log(l) * e1).norm(), 1e-15);
    EXPECT_LE((m.hencky_left - std::log(l) * q * e1 * q.transpose()).norm(), 1e-15);
    EXPECT_NEAR(m.jacobian, l, 1e-15);
    EXPECT_NEAR(m.volumetric_strain, std::log(l), 1e-15);
    EXPECT_NEAR(m.equivalent_shear_strain, std::sqrt(4.0 / 3.0) * std::log(l), 1e-15);
  }
}

TEST(StrainMeasures, SimpleShearMatchesTheClosedForms) {
  for (double g : {0.01, 1.0, 4.0}) {
    const Mat3 f = simple_shear(g);
    const StrainMeasures m = strain_measures(f);
    ASSERT_TRUE(m.valid) << m.reason;
    Mat3 e_ref, a_ref;
    e_ref << 0, g, 0, g, g * g, 0, 0, 0, 0;
    a_ref << 0, g, 0, g, -g * g, 0, 0, 0, 0;
    EXPECT_LE((m.green_lagrange - 0.5 * e_ref).norm(), 1e-15 * (1 + g * g));
    EXPECT_LE((m.euler_almansi - 0.5 * a_ref).norm(), 1e-15 * (1 + g * g));
    EXPECT_NEAR(m.jacobian, 1.0, 1e-15);
    EXPECT_NEAR(m.volumetric_strain, 0.0, 1e-15);
    // Isochoric, principal Hencky strains +-asinh(gamma/2), 0.
    EXPECT_NEAR(m.equivalent_shear_strain, 2.0 * std::asinh(g / 2), 1e-14);
    // ln U against the independent ln C / 2, and ln V = R ln U R^T.
    EXPECT_LE((m.hencky_right - 0.5 * spd_log(m.right_cauchy_green)).norm(), 1e-14);
    EXPECT_LE((m.hencky_left - m.polar.rotation * m.hencky_right * m.polar.rotation.transpose()).norm(),
              1e-14);
  }
}

TEST(StrainMeasures, SmallStrainsKeepTheirRelativeAccuracy) {
  // F = 1 + H with |H| ~ 1e-9. E, e, ln U and ln V must keep the relative accuracy of the H
  // held in F, not the 7 digits left by forming F^T F - 1, 1 - F^-T F^-1 or the ln of
  // singular values near 1. References, exact to O(|H|^3) (1e-18 relative here):
  //   E = (H + H^T + H^T H)/2,  ln U = E - E^2,  e = (h + h^T - h^T h)/2 with h = H - H^2,
  //   ln V = E' - E'^2 with E' = (H + H^T + H H^T)/2.
  Mat3 a;
  a << 0.3, 1.0, -0.2, 0.1, -0.5, 0.4, 0.7, 0.0, 0.2;
  const Mat3 f = Mat3::Identity() + 1e-9 * a;
  const Mat3 h = f - Mat3::Identity();  // exactly the H held in f (Sterbenz)
  const Mat3 e_ref = 0.5 * (h + h.transpose() + h.transpose() * h);
  const Mat3 hc = h - h * h;
  const Mat3 a_ref = 0.5 * (hc + hc.transpose() - hc.transpose() * hc);
  const Mat3 e_left = 0.5 * (h + h.transpose() + h * h.transpose());
  const StrainMeasures m = strain_measures(f);
  ASSERT_TRUE(m.valid) << m.reason;
  const double scale = e_ref.norm();
  const double errs[] = {(m.green_lagrange - e_ref).norm(), (m.euler_almansi - a_ref).norm(),
                         (m.hencky_right - (e_ref - e_ref * e_ref)).norm(),
                         (m.hencky_left - (e_left - e_left * e_left)).norm(),
                         std::abs(m.volumetric_strain - (e_ref - e_ref * e_ref).trace())};
  double worst = 0.0;
  for (double err : errs) {
    worst = std::max(worst, err / scale);
    EXPECT_LE(err, 1e-14 * scale);
  }
  RecordProperty("worst_relative_error_at_strain_1e-9", sci(worst));
}

TEST(StrainMeasures, IncrementalGradientComposesWithThePrevious) {
  const Mat3 f_prev = rotation(Vec3(0, 1, 1), kPi) * simple_shear(0.8) * uniaxial_stretch(1.5);
  const Mat3 f_inc = rotation(Vec3(1, 0, 0), 0.3) * simple_shear(-0.2);
  const IncrementalDeformation inc = incremental_deformation_gradient(f_inc * f_prev, f_prev);
  ASSERT_TRUE(inc.valid) << inc.reason;
  EXPECT_LE((inc.gradient - f_inc).norm(), 1e-14 * f_inc.norm());
}

// ---------------------------------------------------------------- objective rates

namespace {

struct RateErrors {
  double interior = 0.0, all = 0.0;
};

// The largest norm of each rate over the outputs, split into interior and all.
void accumulate(const std::vector<Mat3>& rate, double scale, RateErrors& e) {
  for (std::size_t k = 0; k < rate.size(); ++k) {
    const double v = rate[k].norm() / scale;
    e.all = std::max(e.all, v);
    if (k > 0 && k + 1 < rate.size()) e.interior = std::max(e.interior, v);
  }
}

Mat3 test_stress() {
  Mat3 s;
  s << -2.0e5, 3.0e4, -1.0e4, 3.0e4, -1.2e5, 2.0e4, -1.0e4, 2.0e4, -0.8e5;
  return s;
}

}  // namespace

TEST(ObjectiveRates, CoRotatingStressHasZeroRatesAtSecondOrderInTheOutputInterval) {
  // sigma(t) = Q(t) sigma0 Q(t)^T, Q = exp(t [w]_x), L = [w]_x: all four rates vanish exactly;
  // the computed ones are the differencing error, O(h^2): halving h divides it by 4.
  const Vec3 w(0.4, -0.7, 1.1);
  const Mat3 s0 = test_stress();
  const double scale = w.norm() * s0.norm();
  std::vector<RateErrors> err;
  for (int n : {10, 20, 40, 80}) {  // outputs over 1 s
    std::vector<double> t;
    std::vector<Mat3> s, l, r;
    for (int k = 0; k <= n; ++k) {
      t.push_back(static_cast<double>(k) / n);
      const Mat3 q = rotation(w, w.norm() * t.back());
      s.push_back(q * s0 * q.transpose());
      l.push_back(cross_matrix(w));
      r.push_back(q);
    }
    const ObjectiveRates rates = objective_rates(t, s, l, r);
    ASSERT_TRUE(rates.valid) << rates.reason;
    RateErrors e;
    for (const auto* v : {&rates.jaumann, &rates.green_naghdi, &rates.truesdell, &rates.oldroyd}) {
      accumulate(*v, scale, e);
    }
    err.push_back(e);
  }
  for (std::size_t i = 0; i + 1 < err.size(); ++i) {
    const double order_all = std::log2(err[i].all / err[i + 1].all);
    const double order_interior = std::log2(err[i].interior / err[i + 1].interior);
    EXPECT_NEAR(order_all, 2.0, 0.1);
    EXPECT_NEAR(order_interior, 2.0, 0.1);
    RecordProperty("h=1/" + std::to_string(10 << i) + "_interior_all",
                   sci(err[i].interior) + " " + sci(err[i].all));
  }
  // Leading term for even spacing: |w|^2 h^2 / 6 interior (sigma''' ~ |w|^3 sigma0), twice that
  // at the ends.
  EXPECT_LE(err.back().interior, 0.5 * w.squaredNorm() / (80.0 * 80.0));
}

TEST(ObjectiveRates, ConvectedStressesHaveZeroRatesOnUnevenOutputs) {
  // F(t) = 1 + t A + t^2 B / 2 on unevenly spaced outputs; L = F_dot F^-1 = (A + t B) F^-1.
  //   Truesdell: sigma = F S F^T / J;  Oldroyd: sigma = F S F^T;  Green-Naghdi: sigma = R s0 R^T.
  // Each rate vanishes exactly; the computed one is the differencing error, O(h^2).
  Mat3 a, b;
  a << 0.3, 0.8, 0.0, -0.2, -0.1, 0.3, 0.1, 0.0, 0.2;
  b << -0.2, 0.0, 0.4, 0.3, 0.1, 0.0, 0.0, -0.5, 0.2;
  const Mat3 s0 = test_stress();
  double prev[3] = {0.0, 0.0, 0.0};
  for (int n : {10, 20, 40}) {
    std::vector<double> t;
    std::vector<Mat3> st, so, sg, l, r;
    for (int k = 0; k <= n; ++k) {
      const double x = static_cast<double>(k) / n;
      t.push_back(x + 0.3 * x * x);  // spacing grows by 1.6 over the series
      const double tk = t.back();
      const Mat3 f = Mat3::Identity() + tk * a + 0.5 * tk * tk * b;
      const Mat3 rot = polar_decomposition(f).rotation;
      st.push_back(f * s0 * f.transpose() / f.determinant());
      so.push_back(f * s0 * f.transpose());
      sg.push_back(rot * s0 * rot.transpose());
      l.push_back((a + tk * b) * f.inverse());
      r.push_back(rot);
    }
    const ObjectiveRates rt = objective_rates(t, st, l, {});
    const ObjectiveRates ro = objective_rates(t, so, l, {});
    const ObjectiveRates rg = objective_rates(t, sg, l, r);
    ASSERT_TRUE(rt.valid && ro.valid && rg.valid);
    EXPECT_TRUE(rt.green_naghdi.empty());
    RateErrors et, eo, eg;
    accumulate(rt.truesdell, a.norm() * s0.norm(), et);
    accumulate(ro.oldroyd, a.norm() * s0.norm(), eo);
    accumulate(rg.green_naghdi, a.norm() * s0.norm(), eg);
    const double cur[3] = {et.all, eo.all, eg.all};
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(cur[i], 2.0 / (n * n)) << "rate " << i << " n " << n;
      if (prev[i] > 0.0) {
        EXPECT_NEAR(std::log2(prev[i] / cur[i]), 2.0, 0.25) << "rate " << i << " n " << n;
      }
      prev[i] = cur[i];
    }
    RecordProperty("n=" + std::to_string(n) + "_truesdell_oldroyd_green_naghdi",
                   sci(cur[0]) + " " + sci(cur[1]) + " " + sci(cur[2]));
  }
}

TEST(ObjectiveRates, TimeDerivativeIsExactForQuadraticsOnUnevenOutputs) {
  Mat3 c0, c1, c2;
  c0 << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  c1 = c0.transpose() * 0.5;
  c2 = -c0 * c0 * 0.01;
  const std::vector<double> t = {0.0, 0.1, 0.15, 0.4, 0.45, 1.0};
  std::vector<Mat3> f;
  for (double x : t) f.push_back(c0 + x * c1 + x * x * c2);
  const std::vector<Mat3> d = time_derivative(t, f);
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_LE((d[k] - (c1 + 2.0 * t[k] * c2)).norm(), 1e-12 * c1.norm()) << "output " << k;
  }
}

// ---------------------------------------------------------------- invalid cells

TEST(StrainValidity, TooFewOrDegenerateParticleSetsAreReportedNotNaN) {
  const Vec3 lo(2.0, 0.0, 0.0);
  const std::vector<Vec3> packing = random_packing(200, lo, 0.05, 17);
  const Mat3 f = simple_shear(0.5);
  auto mapped = [&](const std::vector<Vec3>& x) {
    std::vector<Vec3> y;
    for (const Vec3& p : x) y.push_back(f * p);
    return y;
  };
  // 3 particles and none.
  for (int n : {0, 3}) {
    const std::vector<Vec3> x(packing.begin(), packing.begin() + n);
    const AffineFit fit = fit_deformation_gradient(x, mapped(x));
    EXPECT_FALSE(fit.valid);
    EXPECT_NE(fit.reason.find("too few particles"), std::string::npos) << fit.reason;
    EXPECT_TRUE(finite(fit));
  }
  // Coplanar (a tilted plane through the cell), collinear and coincident sets.
  const Vec3 nrm = Vec3(1, 2, -1).normalized();
  std::vector<Vec3> plane, line, point;
  for (const Vec3& p : packing) {
    plane.push_back(p - nrm.dot(p - lo) * nrm);
    line.push_back(lo + nrm * nrm.dot(p - lo));
    point.push_back(lo);
  }
  for (const auto* x : {&plane, &line, &point}) {
    const AffineFit fit = fit_deformation_gradient(*x, mapped(*x));
    EXPECT_FALSE(fit.valid);
    EXPECT_NE(fit.reason.find("degenerate"), std::string::npos) << fit.reason;
    EXPECT_TRUE(finite(fit));
    EXPECT_EQ(fit.gradient, Mat3::Zero());
  }
  // A flat but genuinely 3-D set just above the threshold is still fitted.
  std::vector<Vec3> slab = plane;
  for (std::size_t p = 0; p < slab.size(); ++p) slab[p] += 2e-3 * nrm.dot(packing[p] - lo) * nrm;
  const AffineFit thin = fit_deformation_gradient(slab, mapped(slab));
  EXPECT_TRUE(thin.valid) << thin.reason;
  EXPECT_LE((thin.gradient - f).norm(), 1e-9);
  // Non-finite input and mismatched lengths.
  std::vector<Vec3> bad = packing;
  bad[5].y() = std::nan("");
  EXPECT_NE(fit_deformation_gradient(bad, mapped(packing)).reason.find("non-finite"), std::string::npos);
  EXPECT_TRUE(finite(fit_deformation_gradient(bad, mapped(packing))));
  const std::vector<Vec3> shorter(packing.begin(), packing.begin() + 10);
  EXPECT_FALSE(fit_deformation_gradient(packing, mapped(shorter)).valid);
}

TEST(StrainValidity, InvertedCollapsedOrNonFiniteGradientsAreReportedNotNaN) {
  const Mat3 reflection = Vec3(-1.0, 1.0, 1.0).asDiagonal();
  const Mat3 flat = Vec3(1.0, 1.0, 0.0).asDiagonal();
  Mat3 nan = Mat3::Identity();
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  Mat3 inf = Mat3::Identity();
  inf(0, 0) = std::numeric_limits<double>::infinity();
  const Mat3 squashed = rotation(Vec3(1, 1, 0), 0.4) * Vec3(1.0, 1.0, 1e-9).asDiagonal();
  const std::pair<Mat3, const char*> cases[] = {{reflection, "<= 0"},
                                                {-Mat3::Identity(), "<= 0"},
                                                {flat, "<= 0"},
                                                {0.5 * reflection * simple_shear(2.0), "<= 0"},
                                                {nan, "non-finite"},
                                                {inf, "non-finite"},
                                                {squashed, "near-singular"}};
  for (const auto& [f, why] : cases) {
    const StrainMeasures m = strain_measures(f);
    EXPECT_FALSE(m.valid);
    EXPECT_NE(m.reason.find(why), std::string::npos) << m.reason;
    EXPECT_TRUE(finite(m)) << m.reason;
    const IncrementalDeformation inc = incremental_deformation_gradient(Mat3::Identity(), f);
    EXPECT_FALSE(inc.valid);
    EXPECT_NE(inc.reason.find(why), std::string::npos) << inc.reason;
    EXPECT_TRUE(inc.gradient.allFinite());
  }
}

TEST(StrainValidity, BadStressSeriesAreReported) {
  const std::vector<Mat3> s(3, test_stress()), l(3, Mat3::Zero());
  const std::vector<double> t_bad = {0.0, 1.0, 1.0}, t = {0.0, 1.0, 2.0};
  EXPECT_NE(objective_rates(t_bad, s, l, {}).reason.find("strictly increasing"), std::string::npos);
  EXPECT_NE(objective_rates(std::span(t).first(2), s, l, {}).reason.find("lengths differ"),
            std::string::npos);
  EXPECT_NE(objective_rates(std::span(t).first(1), std::span(s).first(1), std::span(l).first(1), {})
                .reason.find("fewer than 2"),
            std::string::npos);
  std::vector<Mat3> s_nan = s;
  s_nan[1](0, 0) = std::nan("");
  const ObjectiveRates r = objective_rates(t, s_nan, l, {});
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(r.jaumann.empty());
  EXPECT_NE(r.reason.find("non-finite"), std::string::npos);
}
