// Gradation sampling reproduces the mass distribution; fills place grains without
// overlap inside the container; bad curves are refused with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dem/core/error.h"
#include "dem/scene/fill.h"
#include "dem/scene/gradation.h"

using namespace upgrain::dem;

TEST(Gradation, SampledMassFollowsTheCurve) {
  const std::vector<GradationPoint> curve{{1.0e-3, 0.0}, {1.5e-3, 0.3}, {2.5e-3, 1.0}};
  std::mt19937_64 rng(1);
  const auto r = sample_radii(curve, 200000, rng);
  double total = 0, below = 0;
  for (double x : r) {
    const double m = x * x * x;
    total += m;
    if (x <= 1.5e-3) below += m;
    ASSERT_GE(x, 1.0e-3);
    ASSERT_LE(x, 2.5e-3);
  }
  EXPECT_NEAR(below / total, 0.3, 0.01);
}

// The acceptance of the mass-to-number draw against a midpoint sum of (r_min / r(q))^3 over
// the fraction passing q: it sets how many draws a count of grains takes.
TEST(Gradation, SamplingAcceptanceIsTheMeanOfTheAcceptedFraction) {
  const std::vector<GradationPoint> curve{{1.0e-3, 0.0}, {1.5e-3, 0.3}, {2.5e-3, 1.0}};
  const int n = 1000000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double q = (i + 0.5) / n;
    const std::size_t k = q < 0.3 ? 1 : 2;
    const double r = curve[k - 1].radius + (q - curve[k - 1].fraction_passing) /
                                               (curve[k].fraction_passing - curve[k - 1].fraction_passing) *
                                               (curve[k].radius - curve[k - 1].radius);
    sum += std::pow(curve[0].radius / r, 3);
  }
  EXPECT_NEAR(sampling_acceptance(curve), sum / n, 1e-9);
  // Six and a half decades of radius: about one draw in five million accepted.
  EXPECT_LT(sampling_acceptance({{1e-9, 0.0}, {2.5e-3, 1.0}}), 1e-6);
}

TEST(Gradation, InvalidCurvesAreRefused) {
  EXPECT_THROW(validate_gradation({{1e-3, 0.0}}), upgrain::Error);
  EXPECT_THROW(validate_gradation({{1e-3, 0.0}, {0.9e-3, 1.0}}), upgrain::Error);
  EXPECT_THROW(validate_gradation({{1e-3, 0.0}, {2e-3, 0.8}}), upgrain::Error);
  EXPECT_THROW(validate_gradation({{1e-3, 0.2}, {2e-3, 1.0}}), upgrain::Error);
  EXPECT_THROW(validate_gradation({{1e-3, 0.0}, {2e-3, 0.7}, {3e-3, 0.5}, {4e-3, 1.0}}), upgrain::Error);
  EXPECT_NO_THROW(validate_gradation({{1e-3, 0.0}, {2e-3, 1.0}}));
}

namespace {
void expect_valid_fill(const SceneConfig& s) {
  const ParticleStore p = fill_container(s);
  ASSERT_EQ(static_cast<long>(p.size()), s.particles.count);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_GE(p.x[i].x() - p.radius[i], 0.0);
    EXPECT_LE(p.x[i].x() + p.radius[i], s.container.lx);
    EXPECT_GE(p.x[i].y() - p.radius[i], 0.0);
    EXPECT_LE(p.x[i].y() + p.radius[i], s.container.ly);
    EXPECT_GE(p.x[i].z() - p.radius[i], s.fill.bottom_gap - 1e-15);
    for (std::size_t j = i + 1; j < p.size(); ++j)
      ASSERT_GE((p.x[i] - p.x[j]).norm(), p.radius[i] + p.radius[j]) << "particles " << i << " " << j;
  }
  EXPECT_LE(p.x[0].z(), fill_top_height(s));
}
}  // namespace

TEST(Fill, JitteredLatticeHasNoOverlap) {
  SceneConfig s;
  s.particles.count = 700;
  s.container.lx = 0.03;
  s.container.ly = 0.02;
  s.fill.position_jitter = 1.0;
  expect_valid_fill(s);
}

TEST(Fill, RandomPolydisperseHasNoOverlap) {
  SceneConfig s;
  s.particles.count = 600;
  s.particles.gradation = {{1.0e-3, 0.0}, {2.5e-3, 1.0}};
  s.fill.method = FillMethod::random;
  s.container.lx = s.container.ly = 0.03;
  expect_valid_fill(s);
}

TEST(Fill, TooDenseRandomFillIsAnError) {
  SceneConfig s;
  s.particles.count = 300;
  s.fill.method = FillMethod::random;
  s.fill.solid_fraction = 0.7;  // above random close packing: cannot be reached by addition
  s.container.lx = s.container.ly = 0.02;
  EXPECT_THROW(fill_container(s), upgrain::Error);
}
