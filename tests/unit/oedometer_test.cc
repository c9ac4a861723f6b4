// The oedometric reading of a stress path (dem/analysis/oedometer.h): a linear elastic path
// gives back its E and nu exactly; the Hertz lattice's path gives its power law and its
// tangent modulus; the column's closed form tends to the lattice's; bad paths are refused.
#include "dem/analysis/oedometer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dem/core/error.h"

namespace upgrain::dem {
namespace {

TEST(Oedometer, LinearElasticPathGivesBackEAndNu) {
  const double e = 3.0e7, nu = 0.28;
  const double m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double k0 = k0_from_poisson(nu);
  std::vector<OedometerState> path;
  for (double eps = 0.0; eps < 0.01; eps += 0.002) {
    const double sv = 100.0 + m * eps;  // from a prestressed state
    path.push_back({sv, k0 * sv, eps});
  }
  for (const OedometerStep& s : oedometer_steps(path)) {
    EXPECT_NEAR(s.modulus, m, 1e-6 * m);
    EXPECT_NEAR(s.poisson, nu, 1e-12);
    EXPECT_NEAR(s.youngs, e, 1e-6 * e);
  }
  const ElasticEquivalent q = elastic_equivalent(path, 1000.0);
  EXPECT_NEAR(q.modulus, m, 1e-6 * m);
  EXPECT_NEAR(q.exponent, 0.0, 1e-9);
  EXPECT_NEAR(q.k0, k0, 1e-12);
  EXPECT_NEAR(q.poisson, nu, 1e-12);
  EXPECT_NEAR(q.youngs, e, 1e-6 * e);
}

TEST(Oedometer, HertzLatticePathGivesItsPowerLawAndTangentModulus) {
  // sigma = 2/3 E* eps^(3/2), M = E*^(2/3) (3 sigma / 2)^(1/3): the infinite simple-cubic lattice.
  const double e_star = 5e9 / (2.0 * (1.0 - 0.0625));
  std::vector<OedometerState> path;
  for (double sigma = 1e3; sigma < 1e5; sigma *= 1.1) {
    const double eps = std::pow(1.5 * sigma / e_star, 2.0 / 3.0);
    path.push_back({sigma, 0.0, eps});
  }
  const double at = 1.0e4;
  const ElasticEquivalent q = elastic_equivalent(path, at);
  const double tangent = std::cbrt(e_star * e_star * 1.5 * at);
  EXPECT_NEAR(q.exponent, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(q.modulus, tangent, 2e-3 * tangent);  // secants of 10 % stress steps
  EXPECT_EQ(q.k0, 0.0);
  EXPECT_EQ(q.poisson, 0.0);
  EXPECT_NEAR(q.youngs, q.modulus, 1e-12 * q.modulus);  // nu = 0: E = M
  EXPECT_NEAR(q.modulus_stress, at, 1e-12 * at);        // within the range: exp(ln(at))
  // Below the measured range the fit is taken at its lowest step's stress, not extrapolated.
  const ElasticEquivalent low = elastic_equivalent(path, 10.0);
  const std::vector<OedometerStep> steps = oedometer_steps(path);
  EXPECT_NEAR(low.modulus_stress, steps.front().stress, 1e-9 * steps.front().stress);
  EXPECT_NEAR(low.modulus, std::cbrt(e_star * e_star * 1.5 * steps.front().stress), 2e-3 * low.modulus);
}

TEST(Oedometer, HertzColumnTendsToTheLattice) {
  const double e_star = 2.7e9, r = 1e-3, sigma = 2e4;
  const double lattice = std::pow(1.5 * sigma / e_star, 2.0 / 3.0);
  // The two wall contacts (R* = r) close less than a sphere pair (R* = r/2): 2^(1/3) times less.
  for (int n : {1, 3, 10, 1000}) {
    const double column = hertz_column_strain(sigma, e_star, r, n);
    const double expected = lattice * (static_cast<double>(n - 1) + 2.0 * std::pow(2.0, -1.0 / 3.0)) / n;
    EXPECT_NEAR(column, expected, 1e-12 * expected) << n;
  }
  EXPECT_NEAR(hertz_column_strain(sigma, e_star, r, 100000), lattice, 1e-5 * lattice);
}

TEST(Oedometer, BadPathsAreRefused) {
  EXPECT_THROW(oedometer_steps({{100, 50, 0.01}, {200, 90, 0.01}}), Error);
  EXPECT_THROW(elastic_equivalent({{100, 50, 0.0}}, 100.0), Error);
  EXPECT_THROW(elastic_equivalent({{100, 50, 0.0}, {50, 20, 0.01}}, 100.0), Error);  // M < 0
}

}  // namespace
}  // namespace upgrain::dem
