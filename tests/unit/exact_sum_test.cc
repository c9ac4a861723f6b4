// The exact sum (dem/parallel/exact_sum.h): exact whatever the order, magnitude and sign of the
// terms, and the same bits however the terms are divided.
#include "dem/parallel/exact_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using upgrain::dem::ExactSum;

namespace {

double sum_of(const std::vector<double>& terms) {
  ExactSum s;
  for (double t : terms) s.add(t);
  return s.value();
}

TEST(ExactSum, CancellationLeavesTheSmallTermExactly) {
  EXPECT_EQ(sum_of({1e300, 1.0, -1e300}), 1.0);
  EXPECT_EQ(sum_of({1.0, 1e-300, -1.0}), 1e-300);
  // 0.1 + 0.2 - 0.3 in exact arithmetic of the three doubles: 2^-55 (floating point gives
  // 2^-54).
  EXPECT_EQ(sum_of({0.1, 0.2, -0.3}), std::ldexp(1.0, -55));
  EXPECT_EQ(sum_of({}), 0.0);
  EXPECT_EQ(sum_of({-3.5, 1.25}), -2.25);
}

TEST(ExactSum, SubnormalsAndTheLargestDoubles) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double big = std::numeric_limits<double>::max();
  EXPECT_EQ(sum_of({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(sum_of({big, -big, tiny}), tiny);
  EXPECT_EQ(sum_of({big, big, -big}), big);  // the intermediate 2 max is held without overflow
  EXPECT_TRUE(std::isnan(sum_of({1.0, std::numeric_limits<double>::infinity()})));
  EXPECT_TRUE(std::isnan(sum_of({std::numeric_limits<double>::quiet_NaN(), 1.0})));
}

// A million terms spread over 40 decades, both signs: the sum is the same bits in any order
// and divided in any way, and it agrees with a long-double sum of sorted magnitudes to its
// precision.
TEST(ExactSum, OrderAndPartitionDoNotChangeABit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-20.0, 20.0), unit(-1.0, 1.0);
  std::vector<double> terms(1000000);
  for (double& t : terms) t = unit(rng) * std::pow(10.0, exponent(rng));
  const double forward = sum_of(terms);
  std::shuffle(terms.begin(), terms.end(), rng);
  EXPECT_EQ(sum_of(terms), forward);
  std::reverse(terms.begin(), terms.end());
  EXPECT_EQ(sum_of(terms), forward);
  // Seven parts of unequal sizes, merged.
  ExactSum whole;
  std::size_t start = 0;
  for (int part = 0; part < 7; ++part) {
    const std::size_t end = part == 6 ? terms.size() : start + (terms.size() / 10) * (part + 1) / 3;
    ExactSum piece;
    for (std::size_t k = start; k < end; ++k) piece.add(terms[k]);
    whole.add(piece);
    start = end;
  }
  EXPECT_EQ(whole.value(), forward);
  // An independent reference: long double over terms sorted by magnitude (the error of that sum
  // is below 1e6 ulps of long double, far below one ulp of double here).
  std::sort(terms.begin(), terms.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  long double reference = 0.0L;
  for (double t : terms) reference += t;
  EXPECT_NEAR(forward, static_cast<double>(reference), 4.0 * std::abs(forward) * 1e-16);
}

TEST(ExactSum, StateRoundTripsAndContinues) {
  ExactSum a;
  for (int k = 1; k <= 1000; ++k) a.add(1.0 / k);
  const ExactSum b = ExactSum::from_state(a.state());
  EXPECT_EQ(b.value(), a.value());
  ExactSum a2 = a, b2 = b;
  a2.add(-0.5);
  b2.add(-0.5);
  EXPECT_EQ(a2.value(), b2.value());
}

TEST(ExactSum, ManyEqualTermsSumToTheirMultiple) {
  // Every significand bit set; the exact total n (2^53 - 1) 2^-52 is an integer of 75 bits
  // times a power of two, rounded once to double.
  ExactSum s;
  const double t = std::ldexp(static_cast<double>((std::uint64_t{1} << 53) - 1), -52);
  const long n = 3000000;
  for (long k = 0; k < n; ++k) s.add(t);
  // 2n - n 2^-52, rounded once by the subtraction.
  const double expected = 2.0 * static_cast<double>(n) - std::ldexp(static_cast<double>(n), -52);
  EXPECT_LE(std::abs(s.value() - expected), std::nextafter(expected, 1e300) - expected);
  // Merging (which carries) keeps the value.
  ExactSum twice = s;
  twice.add(s);
  EXPECT_LE(std::abs(twice.value() - 2 * expected), 2 * (std::nextafter(expected, 1e300) - expected));
}

}  // namespace
