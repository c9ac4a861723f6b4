// FixedPointSums (dem/parallel/fixed_point_sum.h): the sum does not depend on the order
// of the terms nor on how they are split into partial sums, and it is accurate.
#include "dem/parallel/fixed_point_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <span>
#include <vector>

namespace {

using upgrain::dem::FixedPointSums;

// Terms spanning 30 orders of magnitude with both signs: a plain double sum of them
// depends on the order.
std::vector<double> wide_terms(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 40);
  std::vector<double> t(static_cast<std::size_t>(n));
  for (double& x : t) x = std::ldexp(mantissa(rng), exponent(rng));
  return t;
}

double max_abs(const std::vector<double>& t) {
  double m = 0.0;
  for (double x : t) m = std::max(m, std::abs(x));
  return m;
}

// The sum of `parts` accumulators, as MPI_SUM over int64 limbs does it.
double sum_in_parts(const std::vector<double>& t, double bound, const std::vector<std::size_t>& cuts) {
  FixedPointSums total({bound});
  std::size_t begin = 0;
  for (std::size_t k = 0; k <= cuts.size(); ++k) {
    const std::size_t end = k < cuts.size() ? cuts[k] : t.size();
    FixedPointSums part({bound});
    for (std::size_t i = begin; i < end; ++i) part.add(0, t[i]);
    for (int l = 0; l < FixedPointSums::kLimbs; ++l) total.limbs()[l] += part.limbs()[l];
    begin = end;
  }
  return total.values()[0];
}

TEST(FixedPointSums, SumIsBitwiseIndependentOfOrderAndPartition) {
  std::vector<double> t = wide_terms(20000, 7);
  const double bound = max_abs(t);
  const double reference = sum_in_parts(t, bound, {});
  std::mt19937_64 rng(11);
  bool plain_sum_varies = false;
  const double plain0 = std::accumulate(t.begin(), t.end(), 0.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::shuffle(t.begin(), t.end(), rng);
    std::vector<std::size_t> cuts;
    std::uniform_int_distribution<std::size_t> at(0, t.size());
    for (int c = 0; c < trial % 7; ++c) cuts.push_back(at(rng));
    std::sort(cuts.begin(), cuts.end());
    EXPECT_EQ(sum_in_parts(t, bound, cuts), reference) << "trial " << trial;
    plain_sum_varies = plain_sum_varies || std::accumulate(t.begin(), t.end(), 0.0) != plain0;
  }
  // The test means something: the plain sum of these terms does change with the order.
  EXPECT_TRUE(plain_sum_varies);
}

TEST(FixedPointSums, SumIsAccurateToTheLastBits) {
  const std::vector<double> t = wide_terms(20000, 3);
  const double bound = max_abs(t);
  // Reference: the terms summed in long double (64-bit significand) from the smallest up;
  // its own error is far below a double ulp of the result here. The fixed-point sum is
  // exact to 2^-128 of the bound, then rounded once: within a few ulps.
  long double exact = 0.0L;
  std::vector<double> sorted = t;
  std::sort(sorted.begin(), sorted.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  for (double x : sorted) exact += static_cast<long double>(x);
  const double got = sum_in_parts(t, bound, {});
  EXPECT_NEAR(got, static_cast<double>(exact), 4.0 * std::abs(static_cast<double>(exact)) * 1.2e-16);
}

TEST(FixedPointSums, IntegerTermsAndCancellationAreExact) {
  // 1e16 + 1 - 1e16 in doubles is 0 or 2 depending on order; fixed point gives 1.
  FixedPointSums s({1e16});
  for (double x : {1e16, 1.0, -1e16}) s.add(0, x);
  EXPECT_EQ(s.values()[0], 1.0);
  // A sum that cancels to a tiny residue keeps it: 2^-60 of the bound.
  FixedPointSums c({1.0});
  for (double x : {1.0, std::ldexp(1.0, -60), -1.0}) c.add(0, x);
  EXPECT_EQ(c.values()[0], std::ldexp(1.0, -60));
  // Negative totals, several quantities, a zero bound.
  FixedPointSums m({10.0, 0.0, 3.0});
  for (int i = 0; i < 1000; ++i) {
    m.add(0, -0.5);
    m.add(2, i % 2 ? 0.25 : -0.75);
  }
  const std::vector<double> v = m.values();
  EXPECT_EQ(v[0], -500.0);
  EXPECT_EQ(v[1], 0.0);
  EXPECT_EQ(v[2], -250.0);
}

TEST(FixedPointSums, RefusesABoundThatIsNotFinite) {
  EXPECT_THROW(FixedPointSums({std::nan("")}), std::exception);
  EXPECT_THROW(FixedPointSums({-1.0}), std::exception);
}

}  // namespace

// The limbs are the term 2^-e cut at 2^-32, 2^-64, 2^-96 toward zero and rounded to nearest
// even at 2^-128: the definition, written with the library's std::ldexp, std::trunc and
// std::nearbyint, against the class's multiplications and shifts, at bounds from 2^-1000 to
// 2^1000 (and beyond, where the class itself falls back to std::ldexp), for subnormal terms
// and for terms exactly halfway between two values of the last limb; added one by one (add())
// and all at once (add_terms()).
TEST(FixedPointSums, LimbsAreTheTermCutAndRoundedAsDefined) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 4000; ++trial) {
    const int e = static_cast<int>(rng() % 2100) - 1050;
    const double bound = std::ldexp(1.0 + static_cast<double>(rng() % 1000) / 1000.0, e);
    if (!std::isfinite(bound) || bound == 0.0) continue;
    FixedPointSums sums({bound});
    int exponent = 0;
    (void)std::frexp(bound, &exponent);
    std::array<std::int64_t, FixedPointSums::kLimbs> expected{};
    std::vector<double> terms;
    for (int k = 0; k < 43; ++k) {  // 43: add_terms() has a remainder past its lanes
      double term = bound * unit(rng) * std::ldexp(1.0, -static_cast<int>(rng() % 200));
      if (k % 8 == 0)  // halfway between two values of the last limb
        term = std::ldexp(static_cast<double>(static_cast<int>(rng() % 1000) - 500) + 0.5, exponent - 128);
      if (std::abs(term) > bound) term = std::copysign(bound, term);
      sums.add(0, term);
      terms.push_back(term);
      double x = std::ldexp(term, -exponent);
      for (int l = 0; l < FixedPointSums::kLimbs; ++l) {
        x = std::ldexp(x, 32);
        const double d = l + 1 < FixedPointSums::kLimbs ? std::trunc(x) : std::nearbyint(x);
        expected[static_cast<std::size_t>(l)] += static_cast<std::int64_t>(d);
        x -= d;
      }
    }
    for (int l = 0; l < FixedPointSums::kLimbs; ++l)
      ASSERT_EQ(sums.limbs()[static_cast<std::size_t>(l)], expected[static_cast<std::size_t>(l)])
          << "bound 2^" << exponent << ", limb " << l;
    // add_terms() cuts its limbs elsewhere (to nearest), to the same sum: the same bits, alone and
    // with terms added one by one besides.
    FixedPointSums at_once({bound}), mixed({bound});
    at_once.add_terms(0, terms);
    mixed.add_terms(0, std::span<const double>(terms).first(terms.size() / 2));
    for (std::size_t k = terms.size() / 2; k < terms.size(); ++k) mixed.add(0, terms[k]);
    const double value = sums.values()[0];
    ASSERT_EQ(std::bit_cast<std::uint64_t>(at_once.values()[0]), std::bit_cast<std::uint64_t>(value))
        << "add_terms: bound 2^" << exponent;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(mixed.values()[0]), std::bit_cast<std::uint64_t>(value))
        << "add_terms and add: bound 2^" << exponent;
  }
}
