// The strength reading of a triaxial path (dem/analysis/triaxial.h): the mobilised angle of
// known stress ratios, the dilatancy angle of known strain-rate ratios, and a synthetic path
// with a known peak, dilatancy at the peak and critical state (with a known spread).
#include "dem/analysis/triaxial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dem/core/error.h"

namespace upgrain::dem {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(Triaxial, MobilisedAngleOfKnownRatios) {
  EXPECT_NEAR(mobilised_friction_angle(300.0, 100.0), 30.0, 1e-12);  // sigma_1 = 3 sigma_3
  EXPECT_NEAR(mobilised_friction_angle(100.0, 100.0), 0.0, 1e-12);
  // sigma_1 / sigma_3 = (1 + sin phi) / (1 - sin phi), the passive ratio, for phi = 40.
  const double s = std::sin(40.0 * kDegree);
  EXPECT_NEAR(mobilised_friction_angle(1e3 * (1 + s) / (1 - s), 1e3), 40.0, 1e-10);
  EXPECT_THROW(static_cast<void>(mobilised_friction_angle(-1.0, 0.5)), Error);
}

TEST(Triaxial, MatsuokaNakaiAngleOfKnownStates) {
  // Triaxial compression: the mobilised angle itself.
  const double s = std::sin(30.0 * kDegree);
  EXPECT_NEAR(matsuoka_nakai_angle(1e3 * (1 + s) / (1 - s), 1e3, 1e3), 30.0, 1e-10);
  EXPECT_NEAR(matsuoka_nakai_angle(2.0, 2.0, 2.0), 0.0, 1e-6);
  // Triaxial extension (3, 3, 1) has the invariant of compression (3, 1, 1), I1 I2 / I3 = 35/3,
  // so compression's angle, asin(1/2) = 30 degrees.
  EXPECT_NEAR(matsuoka_nakai_angle(3.0, 3.0, 1.0), 30.0, 1e-10);
  // A plane-strain-like state with b = 1/2 mobilises less than its Mohr-Coulomb angle says.
  EXPECT_LT(matsuoka_nakai_angle(3.0, 2.0, 1.0), mobilised_friction_angle(3.0, 1.0));
  EXPECT_THROW(static_cast<void>(matsuoka_nakai_angle(1.0, 2.0, 0.5)), Error);
  EXPECT_THROW(static_cast<void>(matsuoka_nakai_angle(2.0, 1.0, 0.0)), Error);
}

TEST(Triaxial, DilatancyAngleOfKnownRateRatios) {
  // A sample that neither dilates nor contracts: psi = 0. Dilating at d eps_v / d eps_1 = -1/2:
  // sin psi = 0.5 / 2.5 = 0.2. Isochoric limit of maximum dilation d eps_v = -d eps_1 (eps_3
  // grows by d eps_1): sin psi = 1/3. Contracting gives psi < 0.
  EXPECT_NEAR(triaxial_dilatancy_angle(0.0), 0.0, 1e-14);
  EXPECT_NEAR(std::sin(triaxial_dilatancy_angle(-0.5) * kDegree), 0.2, 1e-14);
  EXPECT_NEAR(std::sin(triaxial_dilatancy_angle(-1.0) * kDegree), 1.0 / 3.0, 1e-14);
  EXPECT_LT(triaxial_dilatancy_angle(0.3), 0.0);
  // Jaky: K0 = 1 - sin 30 = 0.5; the inertial number.
  EXPECT_NEAR(jaky_k0(30.0), 0.5, 1e-14);
  EXPECT_NEAR(inertial_number(0.2, 3e-3, 2500.0, 1000.0), 0.2 * 3e-3 * std::sqrt(2.5), 1e-16);
}

// A path whose mobilised angle rises linearly to 40 degrees at eps_1 = 0.04, stays there to
// 0.06, falls to 30 at 0.1 and then alternates 30 +- 0.5; eps_v contracts at slope 1/2 to 0.03,
// dilates at slope -1/2 to 0.08 (through the peak) and then stays constant. Pieces by state
// index k (eps_1 = 0.002 k), so that no boundary depends on rounding.
std::vector<TriaxialState> synthetic_path() {
  std::vector<TriaxialState> path;
  const double s3 = 1000.0;
  for (int k = 0; k < 100; ++k) {
    const double e1 = 0.002 * k;
    double phi = k <= 20 ? 2.0 * k : k <= 30 ? 40.0 : k <= 50 ? 40.0 - 0.5 * (k - 30) : 30.0;
    if (k >= 50) phi += k % 2 == 0 ? 0.5 : -0.5;
    const double s = std::sin(phi * kDegree);
    const double ev = k <= 15 ? 0.001 * k : k <= 40 ? 0.015 - 0.001 * (k - 15) : -0.01;
    path.push_back({e1, ev, s3 * (1 + s) / (1 - s), s3});
  }
  return path;
}

TEST(Triaxial, SyntheticPathGivesItsPeakDilatancyAndCriticalState) {
  const std::vector<TriaxialState> path = synthetic_path();
  // The window +-0.011 holds 11 states: only around eps_1 = 0.05 do they all lie on the plateau.
  const FrictionStrength f = friction_strength(path, 0.011, 0.5);
  EXPECT_NEAR(f.peak_angle, 40.0, 1e-10);
  EXPECT_NEAR(f.peak_strain, 0.05, 1e-14);
  EXPECT_NEAR(f.peak_rate_ratio, -0.5, 1e-10);
  EXPECT_NEAR(std::sin(f.peak_dilatancy_angle * kDegree), 0.2, 1e-10);
  // The critical part: eps_1 >= 0.5 * 0.198, the 50 states k = 50..99, +-0.5 in turn.
  EXPECT_EQ(f.critical_states, 50);
  EXPECT_NEAR(f.critical_angle, 30.0, 1e-10);
  EXPECT_NEAR(f.critical_spread, 0.5, 1e-10);
  EXPECT_NEAR(f.critical_rate_ratio, 0.0, 1e-12);
  // A zero window takes the single largest state (the first of the plateau) and still fits a
  // line through three states (it and its neighbours).
  const FrictionStrength g = friction_strength(path, 0.0, 0.5);
  EXPECT_NEAR(g.peak_angle, 40.0, 1e-10);
  EXPECT_NEAR(g.peak_strain, 0.04, 1e-14);
  EXPECT_NEAR(g.peak_rate_ratio, -0.5, 1e-10);
}

TEST(Triaxial, BadPathsAreRefused) {
  std::vector<TriaxialState> path = synthetic_path();
  EXPECT_THROW(static_cast<void>(friction_strength({path[0], path[1]}, 0.01, 0.5)), Error);
  EXPECT_THROW(static_cast<void>(friction_strength(path, 0.01, 0.0)), Error);
  path[10].axial_strain = path[9].axial_strain;
  EXPECT_THROW(static_cast<void>(friction_strength(path, 0.01, 0.5)), Error);
}

}  // namespace
}  // namespace upgrain::dem
