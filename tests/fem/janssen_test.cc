// Janssen's slab solution (fem/analytic/janssen.h) against its defining equation and limits,
// and the earth-pressure coefficients (fem/analytic/earth_pressure.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fem/analytic/earth_pressure.h"
#include "fem/analytic/janssen.h"

namespace upgrain::fem {
namespace {

// A 4.5 cm square box with wall friction 0.5 on every wall, K = 0.43, filled 6 cm high.
JanssenColumn square_box() {
  const double D = 0.045, mu = 0.5;
  return {1600.0 * 9.81, D * D, 4.0 * mu * D, 0.43, 0.06};
}

// The slab equilibrium d sigma_v / dd = rho g - (K F / A) sigma_v, sigma_v(0) = 0.
TEST(Janssen, SatisfiesTheSlabEquilibrium) {
  const JanssenColumn j = square_box();
  EXPECT_EQ(j.vertical_pressure(0.0), 0.0);
  const double h = 1e-6;
  for (const double d : {0.001, 0.02, 0.06, 0.5}) {
    const double slope = (j.vertical_pressure(d + h) - j.vertical_pressure(d - h)) / (2.0 * h);
    const double rhs =
        j.unit_weight - j.lateral_ratio * j.friction_perimeter / j.area * j.vertical_pressure(d);
    EXPECT_NEAR(slope, rhs, 1e-6 * j.unit_weight) << d;
  }
  // The square box: A / F = D / (4 mu).
  EXPECT_NEAR(j.decay_length(), 0.045 / (4.0 * 0.5 * 0.43), 1e-15);
}

TEST(Janssen, TendsToHydrostaticWithoutFrictionAndToTheAsymptoteAtDepth) {
  JanssenColumn j = square_box();
  const double deep = j.unit_weight * j.decay_length();
  EXPECT_NEAR(j.vertical_pressure(50.0 * j.decay_length()), deep, 1e-12 * deep);
  j.friction_perimeter = 1e-12;
  EXPECT_NEAR(j.vertical_pressure(0.06), j.unit_weight * 0.06, 1e-9 * j.unit_weight * 0.06);
  j.friction_perimeter = 0.0;
  EXPECT_EQ(j.vertical_pressure(0.06), j.unit_weight * 0.06);
  EXPECT_EQ(j.mean_vertical_stress(0.0, 0.06), -j.unit_weight * 0.03);
  EXPECT_EQ(j.wall_share(), 0.0);
}

// Slab means against Simpson's rule of the profile; the walls' share against the slab means
// (the floor carries sigma_v(H) A, the walls the rest).
TEST(Janssen, SlabMeansAndWallShareAreIntegralsOfTheProfile) {
  const JanssenColumn j = square_box();
  const double z0 = 0.01, z1 = 0.025;
  const int n = 2000;
  double simpson = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    simpson += w * j.vertical_stress(z0 + (z1 - z0) * k / n);
  }
  simpson /= 3.0 * n;
  EXPECT_NEAR(j.mean_vertical_stress(z0, z1), simpson, 1e-12 * std::abs(simpson));
  const double floor_share = j.vertical_pressure(j.height) / (j.unit_weight * j.height);
  EXPECT_NEAR(j.wall_share(), 1.0 - floor_share, 1e-15);
  EXPECT_GT(j.wall_share(), 0.0);
}

TEST(EarthPressure, RankineAndJakyCoefficients) {
  const double phi = 30.0 * std::numbers::pi / 180.0;
  EXPECT_NEAR(rankine_active(phi), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(rankine_passive(phi), 3.0, 1e-14);
  EXPECT_NEAR(jaky_k0(phi), 0.5, 1e-15);
  EXPECT_EQ(rankine_active(0.0), 1.0);
}

}  // namespace
}  // namespace upgrain::fem
