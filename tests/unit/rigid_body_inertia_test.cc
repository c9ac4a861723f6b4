// The rotational inertial moment of the dynamic stress formulas (dem/stress/
// rigid_body_inertia.h) against an independent quadrature of integral rho a (x) y dV over a
// rotated triaxial ellipsoid, and its skew part against Euler's equations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "dem/stress/rigid_body_inertia.h"

using namespace upgrain::dem;

namespace {

// Gauss-Legendre nodes and weights on [-1, 1] (Golub-Welsch would do; 5 points suffice:
// the integrands below are polynomials of low degree in each coordinate).
constexpr int kGauss = 5;
constexpr double kNode[kGauss] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                  0.9061798459386640};
constexpr double kWeight[kGauss] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                    0.4786286704993665, 0.2369268850561891};

// integral over the ellipsoid of density rho of rho a(y) (x) y, with y = Q diag(a,b,c) u,
// u in the unit ball in spherical coordinates; exact for the quadratic integrand.
Mat3 quadrature(const Vec3& semi_axes, const Eigen::Quaterniond& q, double rho, const Vec3& w,
                const Vec3& w_dot) {
  const Mat3 map = q.toRotationMatrix() * semi_axes.asDiagonal();
  const double jac = semi_axes.prod();
  Mat3 sum = Mat3::Zero();
  const int n_phi = 8;  // trapezoidal in phi: exact for trigonometric polynomials of degree < 8
  for (int ir = 0; ir < kGauss; ++ir) {
    const double s = 0.5 * (kNode[ir] + 1.0), ws = 0.5 * kWeight[ir];
    for (int it = 0; it < kGauss; ++it) {
      const double ct = kNode[it], st = std::sqrt(1.0 - ct * ct);
      for (int ip = 0; ip < n_phi; ++ip) {
        const double phi = 2.0 * std::numbers::pi * ip / n_phi;
        const Vec3 u = s * Vec3(st * std::cos(phi), st * std::sin(phi), ct);
        const Vec3 y = map * u;
        const Vec3 a = w_dot.cross(y) + w.cross(w.cross(y));
        const double weight = ws * s * s * kWeight[it] * (2.0 * std::numbers::pi / n_phi) * jac * rho;
        sum += weight * a * y.transpose();
      }
    }
  }
  return sum;
}

}  // namespace

TEST(RigidBodyInertia, MatchesQuadratureOverARotatedTriaxialEllipsoid) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> nd;
  const double rho = 2650.0;
  for (const Vec3& axes : {Vec3(2e-3, 1.6e-3, 1.2e-3), Vec3(1e-3, 0.2e-3, 0.1e-3), Vec3(1e-3, 1e-3, 1e-3)}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Quaterniond q = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
      const Vec3 w(nd(rng) * 50, nd(rng) * 50, nd(rng) * 50);
      const Vec3 w_dot(nd(rng) * 1e4, nd(rng) * 1e4, nd(rng) * 1e4);
      // Textbook principal moments of a solid ellipsoid: J_1 = m (b^2 + c^2) / 5, ...
      const double m = rho * 4.0 / 3.0 * std::numbers::pi * axes.prod();
      const Vec3 sq = axes.cwiseProduct(axes);
      const Mat3 j_body = Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()).asDiagonal() * (m / 5.0);
      const Mat3 theta = second_moment_in_world(second_moment_from_inertia(j_body), q);
      const Mat3 d = rigid_body_inertial_moment(theta, w, w_dot);
      const Mat3 ref = quadrature(axes, q, rho, w, w_dot);
      EXPECT_LE((d - ref).norm(), 1e-12 * ref.norm()) << "axes " << axes.transpose() << "\n"
                                                      << d << "\n"
                                                      << ref;
    }
  }
}

TEST(RigidBodyInertia, SkewPartIsHalfTheTorqueOfEulersEquations) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> nd;
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Quaterniond q = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
    const Mat3 r = q.toRotationMatrix();
    const Mat3 j = r * Vec3(1.0, 2.5, 3.0).asDiagonal() * r.transpose();
    const Vec3 w(nd(rng), nd(rng), nd(rng)), torque(nd(rng), nd(rng), nd(rng));
    const Vec3 w_dot = angular_acceleration(j, w, torque);
    EXPECT_LE((j * w_dot + w.cross(j * w) - torque).norm(), 1e-13 * torque.norm());
    const Mat3 d = rigid_body_inertial_moment(second_moment_from_inertia(j), w, w_dot);
    const Mat3 skew = 0.5 * (d - d.transpose());
    // skew = [T]_x / 2: skew(2,1) = T_x / 2, skew(0,2) = T_y / 2, skew(1,0) = T_z / 2.
    EXPECT_NEAR(skew(2, 1), 0.5 * torque.x(), 1e-13 * (1 + w.squaredNorm()));
    EXPECT_NEAR(skew(0, 2), 0.5 * torque.y(), 1e-13 * (1 + w.squaredNorm()));
    EXPECT_NEAR(skew(1, 0), 0.5 * torque.z(), 1e-13 * (1 + w.squaredNorm()));
  }
}
