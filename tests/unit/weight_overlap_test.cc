// The overlap a grain's weight gives by its contact law, and the runaway-overlap guard's
// diagnosis built on it (dem/scene/weight_overlap.h, dem/engine/guards.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dem/core/material.h"
#include "dem/engine/guards.h"
#include "dem/scene/weight_overlap.h"
#include "dem/time_step.h"

namespace upgrain::dem {
namespace {

SceneConfig resting_scene(double youngs_modulus) {
  SceneConfig s;
  s.particles.radius = 2e-3;
  s.particles.material.youngs_modulus = youngs_modulus;
  s.effects.gravity = true;
  return s;
}

double weight_of(const SceneConfig& s) {
  const double r = s.particles.radius;
  return s.particles.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r * s.gravity;
}

TEST(WeightOverlap, HertzMatchesTheClosedForm) {
  for (double e : {1e3, 1e6, 5e7, 7e10}) {
    const SceneConfig s = resting_scene(e);
    const double r = s.particles.radius;
    const double e_star = effective_youngs_modulus(s.particles.material, s.particles.material);
    // F = 4/3 E* sqrt(R) delta^(3/2) (Johnson 1985, eq. 4.23), solved for delta.
    const double delta = std::pow(3.0 * weight_of(s) / (4.0 * e_star * std::sqrt(r)), 2.0 / 3.0);
    EXPECT_NEAR(weight_overlap_ratio(s), delta / r, 1e-9 * delta / r) << "E = " << e;
  }
}

TEST(WeightOverlap, HookeIsTheWeightOverTheSpring) {
  SceneConfig s = resting_scene(5e7);
  s.contact_law = "hooke";
  s.law_parameters = {{"normal stiffness", 2e3}};
  EXPECT_NEAR(weight_overlap_ratio(s), weight_of(s) / 2e3 / s.particles.radius, 1e-9);
}

TEST(WeightOverlap, NoneWithoutGravity) {
  SceneConfig s = resting_scene(1e3);
  s.effects.gravity = false;
  EXPECT_EQ(weight_overlap_ratio(s), 0.0);
}

TEST(ImpactOverlap, HertzMatchesTheClosedFormAndDoesNotDependOnTheSize) {
  for (double v : {1.0, 50.0, 100.0})
    for (double r : {0.5e-3, 2e-3}) {
      SceneConfig s = resting_scene(5e9);
      s.particles.radius = r;
      const double e_star = effective_youngs_modulus(s.particles.material, s.particles.material);
      // m v^2 / 2 = 8/15 E* sqrt(R) delta^(5/2), m = 4/3 pi rho R^3 (Johnson 1985, eq. 11.23).
      const double expected =
          std::pow(5.0 * std::numbers::pi * s.particles.material.density * v * v / (4.0 * e_star), 0.4);
      EXPECT_NEAR(impact_overlap_ratio(s, v), expected, 1e-9 * expected) << v << " m/s, r " << r;
    }
}

// Stiff grains at a step below the safe one, but an impact speed whose Hertz overlap passes
// the limit: the guard names the impacts, not the step.
TEST(RunawayOverlap, TellsTooFastImpactsFromATooLargeTimeStep) {
  SceneConfig s = resting_scene(5e9);
  s.time_step_rule.impact_speed = 100.0;  // 0.273 of a radius by Hertz
  s.time_step = 0.5 * estimate_time_step(s).safe_step;
  const std::string m = runaway_overlap(0.3, 0.25, 100, 1e-3, s);
  EXPECT_NE(m.find("too soft for the impacts of this scene"), std::string::npos) << m;
  EXPECT_NE(m.find("100 m/s sinks 0.273"), std::string::npos) << m;
  s.time_step_rule.impact_speed = 50.0;  // 0.157 (the overlap goes as v^(4/5))
  EXPECT_NE(runaway_overlap(0.3, 0.25, 100, 1e-3, s).find("is too large for the impacts"), std::string::npos);
}

// Soft grains (E = 1e3 Pa) with a time step far below the safe one: the guard blames the
// stiffness; stiff grains: the time step.
TEST(RunawayOverlap, TellsSoftGrainsFromATooLargeTimeStep) {
  SceneConfig soft = resting_scene(1e3);
  soft.time_step = estimate_time_step(soft).safe_step / 13.0;
  const std::string a = runaway_overlap(0.3, 0.25, 100, 1e-3, soft);
  EXPECT_NE(a.find("too soft for their weight"), std::string::npos) << a;
  EXPECT_EQ(a.find("too large"), std::string::npos) << a;

  SceneConfig stiff = resting_scene(5e7);
  stiff.time_step = 10.0 * estimate_time_step(stiff).safe_step;
  const std::string b = runaway_overlap(0.3, 0.25, 100, 1e-3, stiff);
  EXPECT_NE(b.find("time step"), std::string::npos) << b;
  EXPECT_EQ(b.find("too soft"), std::string::npos) << b;
  EXPECT_TRUE(runaway_overlap(0.2, 0.25, 100, 1e-3, stiff).empty());
}

TEST(StressOverlap, HertzMatchesTheClosedFormAndDoesNotDependOnTheSize) {
  const AssemblyLoad load{.pressure = 3e5, .coordination = 6.0, .solid_fraction = 0.65};
  for (double r : {0.5e-3, 2e-3}) {
    SceneConfig s = resting_scene(1e8);
    s.particles.radius = r;
    const double e_star = effective_youngs_modulus(s.particles.material, s.particles.material);
    // f = 4 pi r^2 p / (Z phi) = 4/3 E* sqrt(r / 2) delta^(3/2) (Johnson 1985, eq. 4.23).
    const double expected = std::pow(3.0 * std::sqrt(2.0) * std::numbers::pi * load.pressure /
                                         (load.coordination * load.solid_fraction * e_star),
                                     2.0 / 3.0);
    EXPECT_NEAR(stress_overlap_ratio(s, load), expected, 1e-9 * expected) << "r " << r;
  }
}

// The median radius of a gradation (d50 / 2) sets the mean force; Hooke's overlap is f / k_n.
TEST(StressOverlap, HookeIsTheMeanForceOverTheSpringAtTheMedianRadius) {
  SceneConfig s = resting_scene(1e8);
  s.contact_law = "hooke";
  s.law_parameters = {{"normal stiffness", 1e5}};
  s.particles.gradation = {{0.8e-3, 0.0}, {1.2e-3, 1.0}};  // median 1.0e-3
  const AssemblyLoad load{.pressure = 1e5, .coordination = 5.0, .solid_fraction = 0.6};
  const double r = 1e-3;
  const double f = 4.0 * std::numbers::pi * r * r * load.pressure / (load.coordination * load.solid_fraction);
  EXPECT_NEAR(stress_overlap_ratio(s, load), f / 1e5 / r, 1e-9);
  EXPECT_EQ(stress_overlap_ratio(s, AssemblyLoad{}), 0.0) << "no load known";
}

// Grains that carry their weight and the scene's impacts but not the stress of the cell they
// fill: the guard names the stress, with its mean overlap, not the time step.
TEST(RunawayOverlap, TellsGrainsTooSoftForTheCellsStress) {
  SceneConfig s = resting_scene(1e8);
  s.effects.gravity = false;
  s.time_step = 0.5 * estimate_time_step(s).safe_step;
  const AssemblyLoad stressed{.pressure = 3.35e5, .coordination = 6.33, .solid_fraction = 0.69};
  const std::string m = runaway_overlap(0.26, 0.25, 100, 1e-3, s, {}, stressed);
  EXPECT_NE(m.find("too soft for the stress they carry"), std::string::npos) << m;
  EXPECT_NE(m.find("mean stress 3.35e+05 Pa"), std::string::npos) << m;
  EXPECT_EQ(m.find("time step "), std::string::npos) << m;
  const AssemblyLoad light{.pressure = 1e2, .coordination = 6.0, .solid_fraction = 0.65};
  EXPECT_NE(runaway_overlap(0.26, 0.25, 100, 1e-3, s, {}, light).find("is too large for the impacts"),
            std::string::npos);
}

}  // namespace
}  // namespace upgrain::dem
