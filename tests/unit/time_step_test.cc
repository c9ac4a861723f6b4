// The critical time step: Rayleigh time by its formula, Hertz time at the impact speed of
// a free fall, and which of the two limits the step.
#include "dem/time_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dem/contact/hertz_mindlin.h"
#include "dem/scene/fill.h"

using namespace upgrain::dem;

TEST(TimeStep, RayleighTimeOfPaperGrains) {
  SceneConfig s;  // r = 1.5 mm, rho = 2650, E = 29 GPa, nu = 0.25
  const auto e = estimate_time_step(s);
  const double g = 29e9 / 2.5;
  const double tr = std::numbers::pi * 1.5e-3 * std::sqrt(2650 / g) / (0.1631 * 0.25 + 0.8766);
  EXPECT_NEAR(e.rayleigh_time, tr, 1e-12 * tr);
}

TEST(TimeStep, ImpactSpeedIsFreeFallFromTheFillTop) {
  SceneConfig s;
  s.particles.count = 100;
  const double top = fill_top_height(s);
  const auto e = estimate_time_step(s);
  EXPECT_NEAR(e.impact_speed, std::sqrt(2 * 9.81 * top), 1e-12);
  const double m = 2650 * 4.0 / 3 * std::numbers::pi * std::pow(1.5e-3, 3);
  const double e_star = 29e9 / (2 * (1 - 0.0625));
  const double t_pp = hertz::contact_duration(e_star, 0.75e-3, 0.5 * m, e.impact_speed);
  const double t_pw = hertz::contact_duration(e_star, 1.5e-3, m, e.impact_speed);
  EXPECT_DOUBLE_EQ(e.hertz_time, std::min(t_pp, t_pw));
  EXPECT_DOUBLE_EQ(e.safe_step, std::min(0.2 * e.rayleigh_time, 0.1 * e.hertz_time));
}

TEST(TimeStep, FastImpactMakesHertzLimiting) {
  SceneConfig s;
  s.time_step_rule.impact_speed = 500.0;
  EXPECT_EQ(estimate_time_step(s).limiting, "Hertz");
  s.time_step_rule.impact_speed = 0.01;
  EXPECT_EQ(estimate_time_step(s).limiting, "Rayleigh");
}
