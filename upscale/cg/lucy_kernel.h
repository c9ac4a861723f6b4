#pragma once
// Lucy's polynomial kernel (Lucy 1977; MercuryCG's "Lucy", Weinhart et al. 2012, Granular
// Matter 14:289): phi(r) = A (1 + 3u)(1 - u)^3 = A (1 - 6u^2 + 8u^3 - 3u^4), u = r/c < 1,
// A = 105 / (16 pi c^3), twice continuously differentiable with compact support. Upgrain's
// width w is the standard deviation along each axis, as for the Gaussian, so that both
// kernels of one w smooth alike: <x^2> = c^2 / 12, hence c = 2 sqrt(3) w. (MercuryCG's
// "width" of a Lucy kernel is its cut-off c.) docs/coarse-graining.md.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "upscale/cg/kernel.h"

namespace upgrain::upscale::cg {

class LucyKernel {
 public:
  static constexpr const char* name = "lucy";
  static constexpr double cutoff_over_width = 2.0 * std::numbers::sqrt3;

  explicit LucyKernel(double width)
      : w_(width),
        c_(cutoff_over_width * width),
        inv_c_(1.0 / c_),
        a_(105.0 / (16.0 * std::numbers::pi * c_ * c_ * c_)) {}
  // The kernel of cut-off c (MercuryCG's Lucy width).
  static LucyKernel with_cutoff(double cutoff) { return LucyKernel(cutoff / cutoff_over_width); }

  [[nodiscard]] double width() const { return w_; }
  [[nodiscard]] double cutoff() const { return c_; }

  [[nodiscard]] double value(double r2) const {
    if (r2 >= c_ * c_) return 0.0;
    const double u = std::sqrt(r2) * inv_c_;
    const double v = 1.0 - u;
    return a_ * (1.0 + 3.0 * u) * v * v * v;
  }
  // phi' = -12 A u (1 - u)^2 / c, so grad phi(d) = -12 A (1 - u)^2 / c^2 d.
  [[nodiscard]] KernelValue value_and_gradient_factor(double r2) const {
    if (r2 >= c_ * c_) return {0.0, 0.0};
    const double u = std::sqrt(r2) * inv_c_;
    const double v = 1.0 - u;
    return {a_ * (1.0 + 3.0 * u) * v * v * v, -12.0 * a_ * v * v * inv_c_ * inv_c_};
  }

  // psi = int_0^1 phi(|d - s l|) ds in closed form. Along the branch's line, with x the
  // signed distance from the foot of the point (in units of c) and t the distance from the
  // line, rho^2 = t^2 + x^2 and
  //   int rho^2 dx = t^2 x + x^3/3,   int rho^4 dx = t^4 x + 2 t^2 x^3/3 + x^5/5,
  //   int rho^3 dx = x (2x^2 + 5t^2) rho / 8 + 3 t^4 asinh(x/t) / 8,
  // so psi = A c / |l| [G(x_hi) - G(x_lo)] with G the antiderivative of 1 - 6 rho^2 + 8 rho^3
  // - 3 rho^4, over the part of the branch inside the ball (the same bounds as the Gaussian's).
  [[nodiscard]] double line_integral(const Vec3& d, const Vec3& l) const {
    const double l2 = l.squaredNorm();
    if (l2 == 0.0) return value(d.squaredNorm());
    const double s0 = d.dot(l) / l2;
    const double t2 = (d - s0 * l).squaredNorm() * inv_c_ * inv_c_;
    if (t2 >= 1.0) return 0.0;
    const double length = std::sqrt(l2) * inv_c_;
    const double half_chord = std::sqrt(1.0 - t2);
    const double lo = std::max(-s0 * length, -half_chord);
    const double hi = std::min((1.0 - s0) * length, half_chord);
    if (lo >= hi) return 0.0;
    const double t = std::sqrt(t2);
    return a_ * (antiderivative(hi, t, t2) - antiderivative(lo, t, t2)) / length;
  }

 private:
  static double antiderivative(double x, double t, double t2) {
    const double x2 = x * x;
    const double rho = std::sqrt(t2 + x2);
    const double i2 = t2 * x + x * x2 / 3.0;
    const double i4 = t2 * t2 * x + 2.0 * t2 * x * x2 / 3.0 + x * x2 * x2 / 5.0;
    // t^4 asinh(x/t) -> 0 as t -> 0.
    const double log_term = t > 0.0 ? 0.375 * t2 * t2 * std::asinh(x / t) : 0.0;
    const double i3 = 0.125 * x * (2.0 * x2 + 5.0 * t2) * rho + log_term;
    return x - 6.0 * i2 + 8.0 * i3 - 3.0 * i4;
  }

  double w_, c_, inv_c_, a_;
};

}  // namespace upgrain::upscale::cg
