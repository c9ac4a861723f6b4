#pragma once
// The Gaussian coarse-graining kernel of MercuryCG (Weinhart, Thornton, Luding & Bokhove
// 2012, Granular Matter 14:289, eq. 36): phi(r) = C exp(-r^2 / (2 w^2)) for r < 3 w, zero
// beyond, with C chosen so that phi integrates to 1 over its ball. w is the standard
// deviation along each axis (of the uncut Gaussian). docs/coarse-graining.md.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "upscale/cg/kernel.h"

namespace upgrain::upscale::cg {

class GaussianKernel {
 public:
  static constexpr const char* name = "gaussian";
  // Cut-off in units of w.
  static constexpr double cutoff_over_width = 3.0;

  explicit GaussianKernel(double width)
      : w_(width),
        c_(cutoff_over_width * width),
        inv_2w2_(0.5 / (width * width)),
        prefactor_(prefactor(width)) {}

  [[nodiscard]] double width() const { return w_; }
  [[nodiscard]] double cutoff() const { return c_; }

  // phi at distance^2 r2; zero at and beyond the cut-off.
  [[nodiscard]] double value(double r2) const {
    return r2 < c_ * c_ ? prefactor_ * std::exp(-r2 * inv_2w2_) : 0.0;
  }
  // phi and the factor g with grad phi(d) = g d (d the vector from the grain to the point):
  // g = phi'(r) / r = -phi / w^2. The jump at the cut-off is not part of it; where it matters
  // (the divergence of the contact stress) the fields use the exact difference of phi at the
  // two ends of a branch instead (docs/coarse-graining.md, "Gradients").
  [[nodiscard]] KernelValue value_and_gradient_factor(double r2) const {
    const double phi = value(r2);
    return {phi, -2.0 * inv_2w2_ * phi};
  }

  // psi = int_0^1 phi(|d - s l|) ds, the kernel integrated along the branch from the grain
  // (d = point - grain) over the branch vector l, in closed form: with s0 = d.l / |l|^2 the
  // foot of the point on the branch's line and t its distance from the line,
  //   psi = C exp(-t^2 / 2w^2) (w sqrt(pi/2) / |l|) [erf(|l|(s_hi - s0) / (sqrt2 w))
  //                                                 - erf(|l|(s_lo - s0) / (sqrt2 w))],
  // where [s_lo, s_hi] is the part of [0, 1] inside the cut-off ball, |s - s0| |l| <
  // sqrt(c^2 - t^2) (Weinhart et al. 2012, appendix, without the cut-off; the clipping to the
  // ball is exact).
  [[nodiscard]] double line_integral(const Vec3& d, const Vec3& l) const {
    const double l2 = l.squaredNorm();
    if (l2 == 0.0) return value(d.squaredNorm());
    const double s0 = d.dot(l) / l2;
    const double t2 = (d - s0 * l).squaredNorm();
    const double half_chord2 = c_ * c_ - t2;
    if (half_chord2 <= 0.0) return 0.0;
    const double length = std::sqrt(l2);
    const double half_chord = std::sqrt(half_chord2);
    // Signed distances along the line from the foot point, clipped to the ball and the branch.
    const double lo = std::max(-s0 * length, -half_chord);
    const double hi = std::min((1.0 - s0) * length, half_chord);
    if (lo >= hi) return 0.0;
    const double k = std::numbers::sqrt2 * w_;
    return prefactor_ * std::exp(-t2 * inv_2w2_) * (w_ * std::sqrt(0.5 * std::numbers::pi) / length) *
           erf_difference(hi / k, lo / k);
  }

  // C = 1 / ((2 pi)^(3/2) w^3 P), P = erf(3/sqrt2) - sqrt(2/pi) 3 exp(-9/2) the mass of the
  // uncut Gaussian inside 3 w (the chi distribution with 3 degrees of freedom).
  static double prefactor(double width) {
    const double x = cutoff_over_width;
    const double inside =
        std::erf(x / std::numbers::sqrt2) - std::sqrt(2.0 / std::numbers::pi) * x * std::exp(-0.5 * x * x);
    return 1.0 / (std::pow(2.0 * std::numbers::pi, 1.5) * width * width * width * inside);
  }

 private:
  // erf(b) - erf(a) for b > a without the cancellation of two values near 1 (or -1).
  static double erf_difference(double b, double a) {
    if (a > 0.0) return std::erfc(a) - std::erfc(b);
    if (b < 0.0) return std::erfc(-b) - std::erfc(-a);
    return std::erf(b) - std::erf(a);
  }

  double w_, c_, inv_2w2_, prefactor_;
};

}  // namespace upgrain::upscale::cg
