// The contact-stiffness tangent (dem/stress/contact_tangent.h) and its Mandel form
// (coupling/femxdem/rve_tangent.h) against hand calculations, and the unbalanced-force ratio
// (dem/engine/unbalanced_force.h) against one.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

#include "coupling/femxdem/rve_tangent.h"
#include "dem/engine/unbalanced_force.h"
#include "dem/stress/contact_tangent.h"

using namespace upgrain;
using dem::ContactStiffness;
using dem::Mat3;
using dem::Vec3;

namespace {

// A simple cubic lattice of touching spheres of pitch a: per grain (volume a^3) one contact along
// each axis, branch a e_d.
std::vector<ContactStiffness> cubic_lattice_cell(double a, double k_n, double k_t) {
  std::vector<ContactStiffness> c;
  for (int d = 0; d < 3; ++d) c.push_back({a * Vec3::Unit(d), Vec3::Unit(d), k_n, k_t});
  return c;
}

}  // namespace

// By hand: D_1111 = k_n a^2 / a^3 (the x contact); D_1212 = k_t a^2 / a^3 (the y contact: K_11 = k_t,
// d_2 = a), D_2121 likewise from the x contact, D_1221 = 0 (no branch with two components), D_1122 = 0.
// In Mandel's notation the shear entry is 2 (D_1212 + D_2121 + 2 D_1221) / 4 = k_t / a, the normal one
// k_n / a, and no coupling of normal to shear or of two normals.
TEST(ContactTangent, SimpleCubicLatticeMatchesTheHandCalculation) {
  const double a = 2e-3, k_n = 3e5, k_t = 1e5;
  const std::vector<ContactStiffness> c = cubic_lattice_cell(a, k_n, k_t);
  const dem::FullTangent d = dem::contact_stiffness_tangent(c, a * a * a);
  EXPECT_DOUBLE_EQ(d(0, 0), k_n / a);  // 11 11
  EXPECT_DOUBLE_EQ(d(1, 1), k_t / a);  // 12 12
  EXPECT_DOUBLE_EQ(d(3, 3), k_t / a);  // 21 21
  EXPECT_DOUBLE_EQ(d(1, 3), 0.0);      // 12 21
  EXPECT_DOUBLE_EQ(d(0, 4), 0.0);      // 11 22
  const fem::Mat6 m = coupling::mandel_tangent(d);
  fem::Mat6 expected = fem::Mat6::Zero();
  for (int k = 0; k < 3; ++k) expected(k, k) = k_n / a;
  for (int k = 3; k < 6; ++k) expected(k, k) = k_t / a;
  EXPECT_LE((m - expected).cwiseAbs().maxCoeff(), 1e-12 * k_n / a) << m;
}

// Any contact list: D is major symmetric (K symmetric), so is its Mandel matrix, which is
// positive semidefinite (sum of k_n (n.eps.d)^2 + k_t |(1 - nn) eps d|^2 >= 0); the tangent of
// the contacts turned by a rotation Q is the tangent turned by Q, and it is linear in 1/V.
TEST(ContactTangent, SymmetricPositiveAndObjective) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.5, 2.0);
  std::vector<ContactStiffness> c;
  for (int k = 0; k < 40; ++k) {
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    c.push_back({1e-3 * u(rng) * n, n, 1e5 * u(rng), 3e4 * u(rng)});
  }
  const double volume = 1e-7;
  const dem::FullTangent d = dem::contact_stiffness_tangent(c, volume);
  EXPECT_LE((d - d.transpose()).cwiseAbs().maxCoeff(), 1e-12 * d.cwiseAbs().maxCoeff());
  const fem::Mat6 m = coupling::mandel_tangent(d);
  EXPECT_LE((m - m.transpose()).cwiseAbs().maxCoeff(), 1e-12 * m.cwiseAbs().maxCoeff());
  const Eigen::SelfAdjointEigenSolver<fem::Mat6> e(0.5 * (m + m.transpose()));
  EXPECT_GE(e.eigenvalues().minCoeff(), -1e-12 * e.eigenvalues().maxCoeff());
  EXPECT_GT(e.eigenvalues().minCoeff(), 0.0) << "40 contacts in every direction: definite";
  // Turned contacts: sigma' = Q sigma Q^T for eps' = Q eps Q^T, so D' : eps' = Q (D : eps) Q^T.
  const Mat3 q = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<ContactStiffness> turned = c;
  for (ContactStiffness& t : turned) {
    t.branch = q * t.branch;
    t.normal = q * t.normal;
  }
  const fem::Mat6 mq = coupling::mandel_tangent(dem::contact_stiffness_tangent(turned, volume));
  Mat3 eps;
  eps << 1, 0.3, -0.2, 0.3, -0.5, 0.4, -0.2, 0.4, 0.8;
  const Mat3 sigma = fem::mandel::to_matrix(m * fem::mandel::from_matrix(eps));
  const Mat3 sigma_q = fem::mandel::to_matrix(mq * fem::mandel::from_matrix(q * eps * q.transpose()));
  EXPECT_LE((sigma_q - q * sigma * q.transpose()).cwiseAbs().maxCoeff(), 1e-12 * sigma.cwiseAbs().maxCoeff());
}

// Two grains pressed together by one contact with a third grain unbalanced: resultants |F| = 0,
// 0 and 2 over the contacts' mean 1.5 (two contacts of 1 and 2, one owned by a ghost left out).
TEST(UnbalancedForce, MeanResultantOverMeanContactForce) {
  const std::vector<Vec3> forces = {Vec3::Zero(), Vec3::Zero(), Vec3(0, 2, 0)};
  const std::vector<dem::ContactSample> contacts = {
      {0, 1, Vec3::Zero(), Vec3(1, 0, 0)},
      {1, 2, Vec3::Zero(), Vec3(0, 0, 2)},
      {3, 0, Vec3::Zero(), Vec3(0, 0, 7)},   // first grain a ghost: counted by its owner
      {0, -1, Vec3::Zero(), Vec3(0, 9, 0)},  // a wall
  };
  EXPECT_DOUBLE_EQ(dem::unbalanced_force_ratio(forces, contacts), (2.0 / 3.0) / 1.5);
  EXPECT_EQ(dem::unbalanced_force_ratio(forces, {}), 0.0);
}
