// The kernels against independent numbers: their integrals by Gauss-Legendre quadrature in
// radius, their gradients by central differences, and their line integrals by composite
// Gauss-Legendre quadrature along the branch, split where the branch crosses the cut-off
// sphere so that every panel's integrand is smooth (docs/coarse-graining.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "cg_helpers.h"
#include "upscale/cg/gaussian_kernel.h"
#include "upscale/cg/lucy_kernel.h"

namespace upgrain::upscale::cg {
namespace {

template <class K>
class KernelTest : public ::testing::Test {};
using Kernels = ::testing::Types<GaussianKernel, LucyKernel>;
TYPED_TEST_SUITE(KernelTest, Kernels);

TYPED_TEST(KernelTest, IntegratesToOneOverItsBall) {
  for (double w : {1e-3, 0.37, 2.0}) {
    const TypeParam k(w);
    // int_0^c 4 pi r^2 phi(r) dr: the integrand is smooth on [0, c) (a polynomial in r for
    // Lucy, of degree 6, which 20 points per panel integrate exactly).
    const double integral = test::gauss_legendre(
        0.0, k.cutoff(), [&](double r) { return 4.0 * std::numbers::pi * r * r * k.value(r * r); }, 64);
    EXPECT_NEAR(integral, 1.0, 1e-13) << w;
  }
}

TEST(LucyKernel, WidthIsTheStandardDeviationAlongAnAxis) {
  const LucyKernel k(0.8);
  // <x^2> = (1/3) int r^2 phi dV.
  const double second = test::gauss_legendre(
      0.0, k.cutoff(),
      [&](double r) { return 4.0 * std::numbers::pi * r * r * r * r * k.value(r * r) / 3.0; }, 64);
  EXPECT_NEAR(std::sqrt(second), 0.8, 1e-13);
  // MercuryCG's Lucy "width" is the cut-off.
  EXPECT_NEAR(LucyKernel::with_cutoff(0.25).cutoff(), 0.25, 1e-16);
}

TYPED_TEST(KernelTest, GradientFactorIsTheDerivativeOfTheValue) {
  const TypeParam k(0.5);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 200; ++n) {
    const Vec3 d(u(rng), u(rng), u(rng));
    if (std::abs(d.norm() - k.cutoff()) < 1e-3) continue;  // the Gaussian's jump
    const KernelValue kv = k.value_and_gradient_factor(d.squaredNorm());
    EXPECT_DOUBLE_EQ(kv.phi, k.value(d.squaredNorm()));
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j) {
      Vec3 e = Vec3::Zero();
      e[j] = h;
      const double fd = (k.value((d + e).squaredNorm()) - k.value((d - e).squaredNorm())) / (2 * h);
      // Central differences: error h^2 phi''' / 6, about 1e-9 of phi / w here.
      EXPECT_NEAR(kv.gradient_factor * d[j], fd, 1e-7 * k.value(0.0) / k.width());
    }
  }
}

// Branches of every kind: inside the ball, crossing it, missing it, through the point, with
// the point beyond either end, short and long.
TYPED_TEST(KernelTest, LineIntegralEqualsQuadratureAlongTheBranch) {
  const TypeParam k(0.3);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  int nonzero = 0;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 d(u(rng), u(rng), u(rng));
    Vec3 l(u(rng), u(rng), u(rng));
    if (n % 7 == 0) l *= 0.01;
    if (n % 11 == 0) l = -2.0 * d;  // the point on the branch
    const double expected = test::line_integral_by_quadrature(k, d, l);
    const double got = k.line_integral(d, l);
    EXPECT_NEAR(got, expected, 1e-12 * k.value(0.0)) << n;
    if (expected > 0.0) ++nonzero;
  }
  EXPECT_GT(nonzero, 500);
}

// For a branch wholly inside the cut-off ball, the Gaussian's line integral is the uncut
// Gaussian's with the renormalised prefactor: C exp(-t^2/2w^2) w sqrt(pi/2)/L (erf(..) -
// erf(..)) with the erf arguments at the branch's ends, written out here from scratch.
TEST(GaussianKernel, LineIntegralInsideTheBallIsTheErfFormula) {
  const double w = 0.4;
  const GaussianKernel k(w);
  const Vec3 d(0.1, -0.2, 0.05), l(-0.3, 0.5, 0.2);
  const double L = l.norm();
  const Vec3 e = l / L;
  const double along = d.dot(e), t2 = (d - along * e).squaredNorm();
  const double expected =
      GaussianKernel::prefactor(w) * std::exp(-t2 / (2 * w * w)) * w * std::sqrt(std::numbers::pi / 2) / L *
      (std::erf(along / (std::numbers::sqrt2 * w)) - std::erf((along - L) / (std::numbers::sqrt2 * w)));
  EXPECT_NEAR(k.line_integral(d, l), expected, 1e-14 * k.value(0.0));
}

}  // namespace
}  // namespace upgrain::upscale::cg
