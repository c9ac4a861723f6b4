#pragma once
// Sums of doubles whose bits do not depend on the order of the terms, nor on how they are
// divided among MPI ranks: each term is cut into four 32-bit limbs of a fixed-point number
// scaled by a bound B on |term| that is the same everywhere, the limbs are summed as
// integers (exact and associative, so MPI_SUM over int64 gives the same bits on any
// partition), and the total is converted back once. This is the fixed-point variant of
// the reproducible summation of Demmel and Nguyen (IEEE Trans. Comput. 64:2060, 2015).
//
// Accuracy: a term is kept to 2^-128 B (the bits below are rounded), so the sum is exact
// to N 2^-128 B before the one rounding of the conversion: a few ulps of the result unless
// the result itself is 2^-70 B or smaller (massive cancellation). Up to 2^31 terms per
// quantity (each limb sum stays below 2^63).
//
// Used where a global sum steers the particle states (FIRE's power and norms,
// dem/engine/relaxation.h) and must therefore be identical on any rank count.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace upgrain::dem {

class FixedPointSums {
 public:
  static constexpr int kLimbs = 4;

  // One bound per quantity, each >= every |term| of that quantity and identical on every
  // rank (an MPI_MAX over the ranks is exact). A zero bound means every term is zero.
  explicit FixedPointSums(std::vector<double> bounds);

  void add(int quantity, double term) {
    // term 2^-e lies in (-1, 1). Each pass shifts 32 bits above the point (exact: a power of
    // two), takes the integer part (exact: |x| < 2^32) and keeps the fraction (exact:
    // Sterbenz); the last limb is rounded to nearest even by the 1.5 2^52 shift (exact for
    // |x| < 2^51, under IEEE arithmetic without -ffast-math). Limbs carry the term's sign, so
    // |limb| < 2^32. Multiplications by powers of two in place of std::ldexp, which is a
    // library call: the sum of a FIRE step's terms took 40-56 ns per term with it.
    const auto q = static_cast<std::size_t>(quantity);
    double x = scale_[q] != 0.0 ? term * scale_[q] : std::ldexp(term, -exponent_[q]);
    std::int64_t* l = limbs_.data() + q * kLimbs;
    for (int k = 0; k + 1 < kLimbs; ++k) {
      x *= 0x1p32;
      const auto i = static_cast<std::int64_t>(x);  // truncation toward zero
      l[k] += i;
      x -= static_cast<double>(i);
    }
    x *= 0x1p32;
    l[kLimbs - 1] += static_cast<std::int64_t>((x + 0x1.8p52) - 0x1.8p52);
  }

  // The limbs of every quantity, to be summed elementwise over ranks (MPI_INT64_T, MPI_SUM).
  [[nodiscard]] std::vector<std::int64_t>& limbs() { return limbs_; }
  [[nodiscard]] const std::vector<std::int64_t>& limbs() const { return limbs_; }
  // The sums, from the (summed) limbs.
  [[nodiscard]] std::vector<double> values() const;
  [[nodiscard]] int quantities() const { return static_cast<int>(exponent_.size()); }

 private:
  std::vector<int> exponent_;  // |term| < 2^exponent
  // 2^-exponent where it is a normal double (the product term 2^-e is then what std::ldexp
  // gives: both are the exact value correctly rounded); 0 where std::ldexp must do it.
  std::vector<double> scale_;
  std::vector<std::int64_t> limbs_;
};

}  // namespace upgrain::dem
