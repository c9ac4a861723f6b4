// The Coulomb wall law (fem/contact/coulomb_friction.h): stick below the limit, slip at it,
// against the slip, and its derivatives against central differences. No MPI, no deal.II.
#include <gtest/gtest.h>

#include <cmath>

#include "fem/contact/coulomb_friction.h"

namespace upgrain::fem {
namespace {

const Eigen::Vector3d wall_normal = Eigen::Vector3d(1.0, 0.0, 0.0);  // the wall x = Lx
constexpr double mu = 0.4, penalty = 1e9, pressure = 2e3;

TEST(CoulombFriction, SticksBelowTheLimitAsATangentialSpring) {
  const Eigen::Vector3d previous(0.0, 100.0, -200.0);  // tangential
  const Eigen::Vector3d du(3e-5, -1e-8, 2e-8);         // the normal part is ignored
  const FrictionResponse r = coulomb_friction(wall_normal, previous, du, pressure, mu, penalty);
  ASSERT_FALSE(r.slipping);
  const Eigen::Vector3d expected = previous - penalty * Eigen::Vector3d(0.0, du[1], du[2]);
  EXPECT_LT((r.traction - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LE(r.traction.norm(), mu * pressure);
}

TEST(CoulombFriction, SlipsAtTheLimitAgainstTheSlip) {
  const Eigen::Vector3d du(0.0, 0.0, -1e-5);  // the body slides down the wall
  const FrictionResponse r =
      coulomb_friction(wall_normal, Eigen::Vector3d::Zero(), du, pressure, mu, penalty);
  ASSERT_TRUE(r.slipping);
  EXPECT_NEAR(r.traction.norm(), mu * pressure, 1e-12 * mu * pressure);
  EXPECT_NEAR(r.traction[2], mu * pressure, 1e-12 * mu * pressure);  // holds the body up
  EXPECT_EQ(r.traction[0], 0.0);
  // No pressure, no friction.
  for (const double p : {0.0, -5.0}) {
    const FrictionResponse free = coulomb_friction(wall_normal, Eigen::Vector3d::Zero(), du, p, mu, penalty);
    EXPECT_EQ(free.traction.norm(), 0.0);
  }
}

// d t / d u and d t / d p against central differences, stick and slip, in directions that
// are not aligned with the axes.
TEST(CoulombFriction, DerivativesMatchFiniteDifferences) {
  const Eigen::Vector3d previous(0.0, 150.0, 300.0);
  for (const Eigen::Vector3d& du :
       {Eigen::Vector3d(1e-9, 2e-8, -3e-8), Eigen::Vector3d(1e-6, -4e-7, -9e-7)}) {
    const FrictionResponse r = coulomb_friction(wall_normal, previous, du, pressure, mu, penalty);
    const double h = 1e-12;
    Eigen::Matrix3d fd;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(k);
      fd.col(k) = (coulomb_friction(wall_normal, previous, du + e, pressure, mu, penalty).traction -
                   coulomb_friction(wall_normal, previous, du - e, pressure, mu, penalty).traction) /
                  (2.0 * h);
    }
    EXPECT_LT((fd - r.d_traction_d_displacement).norm(), 1e-6 * penalty) << "slipping " << r.slipping;
    const double hp = 1e-3;
    const Eigen::Vector3d fd_p =
        (coulomb_friction(wall_normal, previous, du, pressure + hp, mu, penalty).traction -
         coulomb_friction(wall_normal, previous, du, pressure - hp, mu, penalty).traction) /
        (2.0 * hp);
    EXPECT_LT((fd_p - r.d_traction_d_pressure).norm(), 1e-9) << "slipping " << r.slipping;
  }
}

}  // namespace
}  // namespace upgrain::fem
