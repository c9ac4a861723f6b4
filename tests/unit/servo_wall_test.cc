// The servo wall's kernel (dem/boundary/servo_wall.h): on a wall pressing a spring it reaches
// the target stress, with the error shrinking by (1 - alpha) per step on a linear spring, and
// stays stable on a Hertz spring with the stiffness bound; bad settings are refused.
#include "dem/boundary/servo_wall.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dem/contact/hertz_mindlin.h"
#include "dem/core/error.h"

namespace upgrain::dem {
namespace {

constexpr double kDt = 1e-6;

ServoSettings settings(double alpha) { return {2.0e4, 1.0e-4, alpha, 1.0}; }

// A wall pressing a linear spring of stiffness k: stress k u / A at the wall's travel u.
TEST(ServoWall, LinearSpringErrorShrinksByOneMinusAlpha) {
  const double k = 1.0e6;
  for (const double alpha : {0.1, 0.5, 1.0}) {
    const ServoSettings s = settings(alpha);
    const double target_u = s.target_stress * s.area / k;
    double u = 0.5 * target_u;  // started in contact, below the target
    double error = s.target_stress - k * u / s.area;
    for (int step = 0; step < 60; ++step) {
      u += servo_speed(s, k * u / s.area, k, kDt) * kDt;
      const double next = s.target_stress - k * u / s.area;
      // The discrete map of the gain's derivation, e' = (1 - alpha) e.
      EXPECT_NEAR(next, (1.0 - alpha) * error, 1e-9 * s.target_stress) << alpha;
      error = next;
    }
    EXPECT_NEAR(k * u / s.area, s.target_stress, 2e-3 * s.target_stress) << alpha;
  }
}

TEST(ServoWall, ClampedApproachThenConvergence) {
  // Far from the spring: the wall approaches at its maximum speed, then settles on the target.
  const double k = 1.0e6;
  ServoSettings s = settings(0.5);
  s.max_speed = 0.05;
  double u = -1e-4;  // 0.1 mm short of touching
  long clamped = 0;
  for (int step = 0; step < 20000; ++step) {
    const double stress = u > 0.0 ? k * u / s.area : 0.0;
    const double v = servo_speed(s, stress, u > 0.0 ? k : 0.0, kDt);
    EXPECT_LE(std::abs(v), s.max_speed);
    clamped += std::abs(v) == s.max_speed;
    u += v * kDt;
  }
  EXPECT_GT(clamped, 1000);  // 0.1 mm at 0.05 m/s: 2000 steps of approach
  EXPECT_NEAR(k * u / s.area, s.target_stress, 1e-6 * s.target_stress);
}

// A spring whose far end recedes at the speed u: the wall must keep moving at u. The
// proportional servo then lags by exactly e = u / G = u k dt / (alpha A); with the integral term
// the error goes to 0 and the integral to u.
TEST(ServoWall, IntegralTermRemovesTheLagOfAMovingSpring) {
  const double k = 1.0e6, u = 2e-3;
  const ServoSettings s = settings(0.5);
  for (const double beta : {0.0, 0.1, 0.5}) {
    double x = 0.5 * s.target_stress * s.area / k, base = 0.0, integral = 0.0;
    for (int step = 0; step < 2000; ++step) {
      x += servo_speed_with_integral(s, k * (x - base) / s.area, k, kDt, beta, integral) * kDt;
      base += u * kDt;
    }
    const double error = s.target_stress - k * (x - base) / s.area;
    if (beta == 0.0) {
      EXPECT_NEAR(error, u / servo_gain(s, k, kDt), 1e-9 * s.target_stress);
      EXPECT_EQ(integral, 0.0);
    } else {
      EXPECT_NEAR(error, 0.0, 1e-9 * s.target_stress) << beta;
      EXPECT_NEAR(integral, u, 1e-9 * u) << beta;
    }
  }
  // Before contact the wall approaches at the maximum speed and the integral is kept.
  double integral = 1e-3;
  EXPECT_EQ(servo_speed_with_integral(s, 0.0, 0.0, kDt, 0.1, integral), s.max_speed);
  EXPECT_EQ(integral, 1e-3);
}

TEST(ServoWall, HertzSpringWithTheBoundIsStableAndConverges) {
  // N equal Hertz contacts of radius r under the wall (the bound's own case), and N contacts
  // of which a few carry most of the force (the bound above the true stiffness).
  const double e_star = 5e9 / (2.0 * (1.0 - 0.25 * 0.25)), r = 1e-3;
  const double area = 1e-4;
  for (const double n : {100.0, 10.0}) {
    for (const double alpha : {0.2, 1.0}) {
      ServoSettings s{5.0e4, area, alpha, 0.1};
      double u = 1e-9;
      double last_error = s.target_stress;
      bool monotone = true;
      for (int step = 0; step < 4000; ++step) {
        const double f = n * hertz::normal_force(e_star, r, u);
        const double k = hertz_wall_stiffness_bound(f, n, e_star, r);
        // The bound holds: the true stiffness sum N dF/d(delta) is not above it.
        EXPECT_LE(n * hertz::normal_stiffness(e_star, r, u), k * (1.0 + 1e-12));
        u += servo_speed(s, f / area, k, kDt) * kDt;
        const double error = std::abs(s.target_stress - n * hertz::normal_force(e_star, r, u) / area);
        monotone = monotone && error <= last_error * (1.0 + 1e-12);
        EXPECT_LT(error, s.target_stress);
        last_error = error;
      }
      // A Hertz spring stiffens: the step of alpha = 1, exact for the tangent, overshoots the
      // target once from below (then the error is still below the initial one, and shrinks); a
      // smaller alpha approaches it from below, monotonically.
      EXPECT_TRUE(monotone || alpha > 0.5) << "N = " << n << ", alpha = " << alpha;
      EXPECT_LT(last_error, 1e-3 * s.target_stress) << "N = " << n << ", alpha = " << alpha;
    }
  }
  // Unequal contacts: 2 contacts of radius r at overlap u and 8 at u / 4 (touching later);
  // the bound with N = 10 is above their stiffness sum at every travel.
  for (double u = 1e-8; u < 1e-4; u *= 1.5) {
    const double f = 2.0 * hertz::normal_force(e_star, r, u) + 8.0 * hertz::normal_force(e_star, r, u / 4.0);
    const double k =
        2.0 * hertz::normal_stiffness(e_star, r, u) + 8.0 * hertz::normal_stiffness(e_star, r, u / 4.0);
    EXPECT_LE(k, hertz_wall_stiffness_bound(f, 10.0, e_star, r)) << u;
    EXPECT_GT(k, 0.5 * hertz_wall_stiffness_bound(f, 10.0, e_star, r)) << u;
  }
}

TEST(ServoWall, AlphaAboveTwoWouldDiverge) {
  // Why alpha is bounded: the same map with alpha = 2.5 grows (the factor is |1 - alpha| = 1.5).
  const double k = 1.0e6;
  ServoSettings s = settings(2.5);  // past check_servo_settings, which refuses it
  s.max_speed = 1e9;
  double u = 0.5 * s.target_stress * s.area / k;
  const double e0 = s.target_stress - k * u / s.area;
  for (int step = 0; step < 10; ++step) u += servo_speed(s, k * u / s.area, k, kDt) * kDt;
  EXPECT_GT(std::abs(s.target_stress - k * u / s.area), 50.0 * std::abs(e0));
}

TEST(ServoWall, BadSettingsAreRefused) {
  EXPECT_NO_THROW(check_servo_settings(settings(1.0)));
  for (const double alpha : {0.0, -0.5, 1.5, std::nan("")})
    EXPECT_THROW(check_servo_settings(settings(alpha)), Error);
  ServoSettings s = settings(0.5);
  s.area = 0.0;
  EXPECT_THROW(check_servo_settings(s), Error);
  s = settings(0.5);
  s.max_speed = 0.0;
  EXPECT_THROW(check_servo_settings(s), Error);
  s = settings(0.5);
  s.target_stress = -1.0;
  EXPECT_THROW(check_servo_settings(s), Error);
}

}  // namespace
}  // namespace upgrain::dem
