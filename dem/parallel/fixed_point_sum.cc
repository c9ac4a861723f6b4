#include "dem/parallel/fixed_point_sum.h"

#include <cmath>
#include <string>

#include "dem/core/error.h"

namespace upgrain::dem {

FixedPointSums::FixedPointSums(std::vector<double> bounds)
    : exponent_(bounds.size(), 0), scale_(bounds.size(), 0.0), limbs_(bounds.size() * kLimbs, 0) {
  for (std::size_t q = 0; q < bounds.size(); ++q) {
    if (!std::isfinite(bounds[q]) || bounds[q] < 0.0)
      throw Error("fixed-point sum: bound " + std::to_string(bounds[q]) + " of quantity " +
                  std::to_string(q) + " is not a finite non-negative number");
    // frexp: bound = f 2^e with f in [0.5, 1), so every |term| <= bound < 2^e.
    if (bounds[q] > 0.0) (void)std::frexp(bounds[q], &exponent_[q]);
    if (exponent_[q] >= -1000 && exponent_[q] <= 1000) scale_[q] = std::ldexp(1.0, -exponent_[q]);
  }
}

std::vector<double> FixedPointSums::values() const {
  std::vector<double> out(exponent_.size(), 0.0);
  for (std::size_t q = 0; q < exponent_.size(); ++q) {
    // Carry so that limbs 1..3 lie in [0, 2^32) and limb 0 holds the sign; the value is
    // then sum_k L_k 2^(-32 (k + 1)) 2^e, evaluated from the smallest limb up in long
    // double (64-bit significand) and rounded once to double.
    std::array<std::int64_t, kLimbs> l{};
    for (int k = 0; k < kLimbs; ++k) l[k] = limbs_[q * kLimbs + k];
    for (int k = kLimbs - 1; k > 0; --k) {
      const std::int64_t carry = l[k] >> 32;  // floor division by 2^32 (arithmetic shift)
      l[k] -= carry * (std::int64_t{1} << 32);
      l[k - 1] += carry;
    }
    long double v = 0.0L;
    for (int k = kLimbs - 1; k >= 0; --k) v = std::ldexp(v + static_cast<long double>(l[k]), -32);
    out[q] = static_cast<double>(std::ldexp(v, exponent_[q]));
  }
  return out;
}

}  // namespace upgrain::dem
