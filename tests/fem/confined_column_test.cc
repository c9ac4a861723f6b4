// The exact solution itself (fem/analytic/confined_column.h), checked against the BVP it
// claims to solve: equilibrium, boundary conditions, Hooke's law and the closed-form norms.
#include <gtest/gtest.h>

#include <cmath>

#include "fem/analytic/confined_column.h"

namespace upgrain::fem {
namespace {

// A 6 cm bed of bulk density 1600 kg/m^3 treated as a continuum with E = 50 MPa, nu = 0.3.
constexpr ConfinedColumn column{1600.0 * 9.81, 0.06, 5.0e7, 0.3};

TEST(ConfinedColumn, ElasticConstants) {
  EXPECT_DOUBLE_EQ(analytic_k0(0.3), 0.3 / 0.7);
  EXPECT_DOUBLE_EQ(analytic_k0(0.0), 0.0);
  const double lambda = column.lame_lambda(), mu = column.shear_modulus();
  EXPECT_NEAR(column.constrained_modulus(), lambda + 2.0 * mu, 1e-12 * lambda);
  EXPECT_NEAR(column.k0(), lambda / (lambda + 2.0 * mu), 1e-15);
  // E = mu (3 lambda + 2 mu) / (lambda + mu): the Lame pair is consistent with (E, nu).
  EXPECT_NEAR(mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu), column.youngs_modulus, 1e-6);
}

TEST(ConfinedColumn, SolvesTheBoundaryValueProblem) {
  const double H = column.height, M = column.constrained_modulus();
  EXPECT_EQ(column.vertical_displacement(0.0), 0.0);  // floor
  EXPECT_EQ(column.vertical_stress(H), 0.0);          // free top
  for (double z : {0.0, 0.013, 0.03, 0.059}) {
    // Hooke: sigma_zz = M du_z/dz (central difference, exact for a quadratic up to round-off).
    const double h = 1e-4;
    const double dudz = (column.vertical_displacement(z + h) - column.vertical_displacement(z - h)) / (2 * h);
    EXPECT_NEAR(M * dudz, column.vertical_stress(z), 1e-9 * column.unit_weight * H);
    // Equilibrium: d(sigma_zz)/dz - rho g = 0.
    const double dsdz = (column.vertical_stress(z + h) - column.vertical_stress(z - h)) / (2 * h);
    EXPECT_NEAR(dsdz, column.unit_weight, 1e-9 * column.unit_weight);
  }
  EXPECT_NEAR(column.mean_vertical_stress(0.0, H), -0.5 * column.unit_weight * H, 1e-12);
}

TEST(ConfinedColumn, ClosedFormNormsMatchQuadrature) {
  // Midpoint rule with many slabs: error O(n^-2) relative.
  const int n = 20000;
  const double H = column.height, dz = H / n, area = 0.045 * 0.045, k = column.k0();
  double u2 = 0.0, s2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = (i + 0.5) * dz;
    u2 += std::pow(column.vertical_displacement(z), 2) * dz;
    s2 += (1.0 + 2.0 * k * k) * std::pow(column.vertical_stress(z), 2) * dz;
  }
  EXPECT_NEAR(std::sqrt(area * u2) / column.displacement_l2_norm(area), 1.0, 1e-8);
  EXPECT_NEAR(std::sqrt(area * s2) / column.stress_l2_norm(area), 1.0, 1e-8);
}

}  // namespace
}  // namespace upgrain::fem
