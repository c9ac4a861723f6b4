// Scalar Hertz-Mindlin kernels against independent expectations: derivatives by finite
// differences, and the contact duration by integrating m* d'' = -F(d) with RK4.
#include "dem/contact/hertz_mindlin.h"

#include <gtest/gtest.h>

#include <cmath>

namespace h = upgrain::dem::hertz;

TEST(HertzNormal, StiffnessIsDerivativeOfForce) {
  const double e = 1.5e10, r = 7.5e-4;
  for (double d : {1e-9, 1e-7, 1e-5}) {
    const double eps = d * 1e-6;
    const double fd = (h::normal_force(e, r, d + eps) - h::normal_force(e, r, d - eps)) / (2 * eps);
    EXPECT_NEAR(h::normal_stiffness(e, r, d), fd, 1e-7 * fd);
  }
}

TEST(HertzNormal, ForceIsDerivativeOfEnergy) {
  const double e = 1.5e10, r = 7.5e-4;
  for (double d : {1e-9, 1e-7, 1e-5}) {
    const double eps = d * 1e-6;
    const double fd = (h::normal_energy(e, r, d + eps) - h::normal_energy(e, r, d - eps)) / (2 * eps);
    EXPECT_NEAR(h::normal_force(e, r, d), fd, 1e-7 * fd);
  }
}

TEST(HertzNormal, OverlapForForceInvertsForce) {
  const double e = 2e7, r = 1e-3;
  for (double d : {1e-8, 3e-6, 2e-4}) {
    EXPECT_NEAR(h::overlap_for_force(e, r, h::normal_force(e, r, d)), d, 1e-12 * d + 1e-20);
  }
}

TEST(HertzNormal, ContactDurationMatchesDirectIntegration) {
  const double e = 1.2e9, r = 5e-4, m = 2e-5, v = 0.7;
  // RK4 on the undamped Hertz impact; independent of the closed form.
  double d = 0.0, u = v, t = 0.0;
  const double dt = h::contact_duration(e, r, m, v) / 200000.0;
  auto acc = [&](double x) { return x > 0 ? -h::normal_force(e, r, x) / m : 0.0; };
  do {
    const double k1x = u, k1v = acc(d);
    const double k2x = u + 0.5 * dt * k1v, k2v = acc(d + 0.5 * dt * k1x);
    const double k3x = u + 0.5 * dt * k2v, k3v = acc(d + 0.5 * dt * k2x);
    const double k4x = u + dt * k3v, k4v = acc(d + dt * k3x);
    d += dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    u += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    t += dt;
  } while (d > 0.0);
  EXPECT_NEAR(h::contact_duration(e, r, m, v), t, 2e-4 * t);
  EXPECT_NEAR(-u, v, 1e-9 * v);  // elastic: leaves at the impact speed
}

TEST(MindlinTangential, StiffnessRatioToNormal) {
  // k_t / k_n = 4 G* / E* ; for equal materials 2(1-nu)/(2-nu) (Johnson eq. 7.42).
  const double nu = 0.25, e = 29e9, g = e / (2 * (1 + nu));
  const double e_star = e / (2 * (1 - nu * nu));
  const double g_star = g / (2 * (2 - nu));
  const double ratio = h::tangential_stiffness(g_star, 1e-3, 1e-6) / h::normal_stiffness(e_star, 1e-3, 1e-6);
  EXPECT_NEAR(ratio, 2 * (1 - nu) / (2 - nu), 1e-14);
}
