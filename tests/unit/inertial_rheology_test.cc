// The mu(I) and phi(I) fits (dem/analysis/inertial_rheology.h): the parameters of a curve
// sampled without noise come back to round-off; a noisy sample of it gives back the curve
// within the noise; a straight line's points leave I0 unbounded and say so; too few points are
// refused.
#include "dem/analysis/inertial_rheology.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "dem/core/error.h"

namespace upgrain::dem {
namespace {

// Glass beads: mu_s = tan 20.9 deg, mu_2 = tan 32.76 deg, I0 = 0.279 (Jop, Forterre & Pouliquen
// 2006, Nature 441, 727).
MuOfI glass_beads() {
  constexpr double deg = std::numbers::pi / 180.0;
  MuOfI m;
  m.mu_s = std::tan(20.9 * deg);
  m.mu_2 = std::tan(32.76 * deg);
  m.i0 = 0.279;
  return m;
}

const std::vector<double> kI = {1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0};

TEST(InertialRheology, MuOfIOfAnExactCurveComesBack) {
  const MuOfI truth = glass_beads();
  std::vector<double> mu;
  for (double i : kI) mu.push_back(truth(i));
  const MuOfI f = fit_mu_of_i(kI, mu);
  EXPECT_NEAR(f.mu_s, truth.mu_s, 1e-8);
  EXPECT_NEAR(f.mu_2, truth.mu_2, 1e-8);
  EXPECT_NEAR(f.i0, truth.i0, 1e-7);
  EXPECT_LT(f.rms, 1e-10);
  EXPECT_FALSE(f.i0_at_bound);
}

TEST(InertialRheology, MuOfIOfANoisySampleStaysWithinTheNoise) {
  // +-0.005 alternating: the fitted curve within 0.005 of the truth over the sampled range.
  const MuOfI truth = glass_beads();
  std::vector<double> mu;
  for (std::size_t k = 0; k < kI.size(); ++k) mu.push_back(truth(kI[k]) + (k % 2 ? 0.005 : -0.005));
  const MuOfI f = fit_mu_of_i(kI, mu);
  EXPECT_LE(f.rms, 0.005 + 1e-12);
  for (double i : kI) EXPECT_NEAR(f(i), truth(i), 0.005);
  EXPECT_NEAR(f.mu_s, truth.mu_s, 0.01);
}

TEST(InertialRheology, AStraightLineLeavesI0Unbounded) {
  // mu = 0.26 + 1.1 I has no saturation in the sampled range: I0 runs to the end of the search.
  std::vector<double> mu;
  const std::vector<double> i = {0.01, 0.05, 0.1, 0.2};
  for (double x : i) mu.push_back(0.26 + 1.1 * x);
  const MuOfI f = fit_mu_of_i(i, mu);
  EXPECT_TRUE(f.i0_at_bound);
  EXPECT_NEAR(f.i0, 2.0, 1e-6);  // ten times the largest I
  // With I at most a tenth of I0, the curve bends by a few thousandths over the range.
  for (std::size_t k = 0; k < i.size(); ++k) EXPECT_NEAR(f(i[k]), mu[k], 5e-3);
}

TEST(InertialRheology, PhiOfIIsTheLeastSquaresLine) {
  std::vector<double> phi;
  for (double i : kI) phi.push_back(0.60 - 0.35 * i);
  const PhiOfI f = fit_phi_of_i(kI, phi);
  EXPECT_NEAR(f.phi_max, 0.60, 1e-14);
  EXPECT_NEAR(f.slope, 0.35, 1e-13);
  EXPECT_LT(f.rms, 1e-14);
}

TEST(InertialRheology, RefusesTooFewOrBadPoints) {
  const std::vector<double> two = {0.01, 0.1}, mu2 = {0.3, 0.4};
  EXPECT_THROW(static_cast<void>(fit_mu_of_i(two, mu2)), Error);
  const std::vector<double> repeated = {0.01, 0.01, 0.1}, mu3 = {0.3, 0.31, 0.4};
  EXPECT_THROW(static_cast<void>(fit_mu_of_i(repeated, mu3)), Error);
  const std::vector<double> negative = {-0.01, 0.01, 0.1};
  EXPECT_THROW(static_cast<void>(fit_mu_of_i(negative, mu3)), Error);
  EXPECT_THROW(static_cast<void>(fit_mu_of_i(two, mu3)), Error);
  const std::vector<double> one = {0.1}, phi1 = {0.6};
  EXPECT_THROW(static_cast<void>(fit_phi_of_i(one, phi1)), Error);
}

}  // namespace
}  // namespace upgrain::dem
