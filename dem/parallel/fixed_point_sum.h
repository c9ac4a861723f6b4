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
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace upgrain::dem {

class FixedPointSums {
 public:
  static constexpr int kLimbs = 4;

  // One bound per quantity, each >= every |term| of that quantity and identical on every
  // rank (an MPI_MAX over the ranks is exact). A zero bound means every term is zero.
  explicit FixedPointSums(std::vector<double> bounds);

  void add(int quantity, double term) {
    const auto q = static_cast<std::size_t>(quantity);
    add_limbs(scale_[q] != 0.0 ? term * scale_[q] : std::ldexp(term, -exponent_[q]),
              limbs_.data() + q * kLimbs);
  }

  // Every term of `terms` to one quantity, the same sum as add() term by term. The limbs are cut
  // here at the nearest integer instead of toward zero, in doubles: the cuts are exact either
  // way and only the last limb rounds, at the same place and to the same nearest-even value (the
  // two residues differ by an integer), so the sum the limbs represent is the same bits, while
  // the loop needs no conversion to integers and runs several terms per instruction. The limbs'
  // sums stay exact as doubles for 2^20 terms (|limb| <= 2^32); each such chunk goes to the
  // integer limbs.
  void add_terms(int quantity, std::span<const double> terms) {
    const auto q = static_cast<std::size_t>(quantity);
    const double scale = scale_[q];
    if (scale == 0.0) {
      for (double t : terms) add(quantity, t);
      return;
    }
    constexpr std::size_t kLanes = 4, kChunk = std::size_t{1} << 20;
    constexpr double kRound = 0x1.8p52;  // x + kRound - kRound: x to the nearest even integer
    for (std::size_t begin = 0; begin < terms.size(); begin += kChunk) {
      const std::size_t end = std::min(terms.size(), begin + kChunk);
      double sum[kLimbs][kLanes] = {};
      std::size_t i = begin;
      for (; i + kLanes <= end; i += kLanes)
        for (std::size_t lane = 0; lane < kLanes; ++lane) {
          double x = terms[i + lane] * scale;
          for (int k = 0; k < kLimbs; ++k) {
            x *= 0x1p32;
            const double limb = (x + kRound) - kRound;
            sum[k][lane] += limb;
            x -= limb;
          }
        }
      std::int64_t* l = limbs_.data() + q * kLimbs;
      for (int k = 0; k < kLimbs; ++k)
        for (std::size_t lane = 0; lane < kLanes; ++lane) l[k] += static_cast<std::int64_t>(sum[k][lane]);
      for (; i < end; ++i) add_limbs(terms[i] * scale, l);
    }
  }

  // The limbs of every quantity, to be summed elementwise over ranks (MPI_INT64_T, MPI_SUM).
  [[nodiscard]] std::vector<std::int64_t>& limbs() { return limbs_; }
  [[nodiscard]] const std::vector<std::int64_t>& limbs() const { return limbs_; }
  // The sums, from the (summed) limbs.
  [[nodiscard]] std::vector<double> values() const;
  [[nodiscard]] int quantities() const { return static_cast<int>(exponent_.size()); }

 private:
  // The limbs of a scaled term x = term 2^-e, which lies in (-1, 1). Each pass shifts 32 bits
  // above the point (exact: a power of two), takes the integer part (exact: |x| < 2^32) and keeps
  // the fraction (exact: Sterbenz); the last limb is rounded to nearest even by the 1.5 2^52 shift
  // (exact for |x| < 2^51, under IEEE arithmetic without -ffast-math). Limbs carry the term's sign,
  // so |limb| < 2^32. Multiplications by powers of two in place of std::ldexp, which is a library
  // call: the sum of a FIRE step's terms took 40-56 ns per term with it.
  static void add_limbs(double x, std::int64_t* l) {
    for (int k = 0; k + 1 < kLimbs; ++k) {
      x *= 0x1p32;
      const auto i = static_cast<std::int64_t>(x);  // truncation toward zero
      l[k] += i;
      x -= static_cast<double>(i);
    }
    x *= 0x1p32;
    l[kLimbs - 1] += static_cast<std::int64_t>((x + 0x1.8p52) - 0x1.8p52);
  }

  std::vector<int> exponent_;  // |term| < 2^exponent
  // 2^-exponent where it is a normal double (the product term 2^-e is then what std::ldexp
  // gives: both are the exact value correctly rounded); 0 where std::ldexp must do it.
  std::vector<double> scale_;
  std::vector<std::int64_t> limbs_;
};

}  // namespace upgrain::dem
