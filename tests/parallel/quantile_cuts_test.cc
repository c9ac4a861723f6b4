// The load-balance kernels without MPI (dem/parallel/load_balance.h): histogram bins, the
// quantile cuts of a cost histogram, and the clamp that keeps interior blocks at least the
// interaction range thick.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "dem/parallel/load_balance.h"

using namespace upgrain::dem;

namespace {

// The cost of a histogram below x, cost uniform inside each bin (the model of quantile_cuts).
double cost_below(const std::vector<long>& h, double lo, double hi, double x) {
  const double w = (hi - lo) / static_cast<double>(h.size());
  double c = 0.0;
  for (std::size_t b = 0; b < h.size(); ++b) {
    const double a = lo + b * w;
    if (x >= a + w)
      c += static_cast<double>(h[b]);
    else if (x > a)
      c += static_cast<double>(h[b]) * (x - a) / w;
  }
  return c;
}

}  // namespace

TEST(QuantileCuts, BinsSendOutsidePointsToTheEndBins) {
  EXPECT_EQ(balance_bin(-1.0, 0.0, 1.0, 10), 0);
  EXPECT_EQ(balance_bin(0.0, 0.0, 1.0, 10), 0);
  EXPECT_EQ(balance_bin(0.05, 0.0, 1.0, 10), 0);
  EXPECT_EQ(balance_bin(0.15, 0.0, 1.0, 10), 1);
  EXPECT_EQ(balance_bin(0.999, 0.0, 1.0, 10), 9);
  EXPECT_EQ(balance_bin(1.0, 0.0, 1.0, 10), 9);
  EXPECT_EQ(balance_bin(7.0, 0.0, 1.0, 10), 9);
}

TEST(QuantileCuts, UniformCostGivesEquallySpacedCuts) {
  const std::vector<long> h(100, 3);
  const std::vector<double> c = quantile_cuts(h.data(), 100, 0.0, 0.06, 4);
  ASSERT_EQ(c.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 0.015 * (k + 1), 1e-15);
  EXPECT_TRUE(quantile_cuts(h.data(), 100, 0.0, 0.06, 1).empty());
  // An empty histogram (no particles) keeps the equal spacing.
  const std::vector<long> zero(100, 0);
  const std::vector<double> e = quantile_cuts(zero.data(), 100, 0.0, 0.06, 3);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_NEAR(e[0], 0.02, 1e-15);
  EXPECT_NEAR(e[1], 0.04, 1e-15);
}

TEST(QuantileCuts, CostInOneCornerIsSplitIntoEqualShares) {
  // Cost piled into the first tenth of the axis, growing towards the wall: the cuts move
  // into that tenth, and the cost between consecutive cuts is total / parts.
  std::vector<long> h(kBalanceBins, 0);
  for (int b = 0; b < kBalanceBins / 10; ++b) h[b] = 1 + (kBalanceBins / 10 - b) % 7 + (b < 50 ? 40 : 0);
  long total = 0;
  for (long v : h) total += v;
  for (int parts = 2; parts <= 8; ++parts) {
    const std::vector<double> c = quantile_cuts(h.data(), kBalanceBins, 0.0, 1.0, parts);
    ASSERT_EQ(c.size(), static_cast<std::size_t>(parts - 1));
    for (int k = 0; k + 1 < parts; ++k) {
      EXPECT_LT(c[k], 0.1);
      if (k > 0) {
        EXPECT_GT(c[k], c[k - 1]);
      }
      EXPECT_NEAR(cost_below(h, 0.0, 1.0, c[k]), static_cast<double>(total) * (k + 1) / parts, 1e-6 * total)
          << parts << " parts, cut " << k;
    }
  }
}

TEST(QuantileCuts, AllCostInOneBinIsInterpolatedInsideIt) {
  std::vector<long> h(10, 0);
  h[6] = 40;
  const std::vector<double> c = quantile_cuts(h.data(), 10, 0.0, 1.0, 4);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_NEAR(c[0], 0.625, 1e-15);
  EXPECT_NEAR(c[1], 0.65, 1e-15);
  EXPECT_NEAR(c[2], 0.675, 1e-15);
}

TEST(QuantileCuts, ClampKeepsInteriorBlocksAtLeastTheRangeThick) {
  const double lo = 0.0, hi = 0.06, m = 0.005;
  // Cuts piled together (a thin sheet of grains) spread to the range, centred forward.
  std::vector<double> c{0.03, 0.03, 0.03};
  clamp_cuts(c, lo, hi, m);
  EXPECT_NEAR(c[0], 0.03, 1e-15);
  EXPECT_GE(c[1] - c[0], m);
  EXPECT_GE(c[2] - c[1], m);
  EXPECT_NEAR(c[2], 0.04, 1e-15);
  // Piled against the upper face: pushed back inside, gaps kept.
  std::vector<double> top{0.06, 0.06, 0.06};
  clamp_cuts(top, lo, hi, m);
  EXPECT_EQ(top[2], hi);
  EXPECT_GE(top[2] - top[1], m);
  EXPECT_GE(top[1] - top[0], m);
  EXPECT_NEAR(top[0], 0.05, 1e-15);
  // Cuts that already satisfy the rule are left alone (the outer blocks may be thin: they
  // are open outwards).
  std::vector<double> fine{0.001, 0.02, 0.059};
  const std::vector<double> before = fine;
  clamp_cuts(fine, lo, hi, m);
  EXPECT_EQ(fine, before);
  // Random piles: the gaps hold exactly in floating point, inside the box, and the clamp is
  // idempotent. The tightest feasible case: 11 cuts, 10 interior blocks in a box of 12.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double a = 1234.5 * u(rng) - 600.0, l = 0.001 + u(rng), mm = l / 12.0;
    std::vector<double> q(11);
    const double centre = a + l * u(rng), spread = mm * 3.0 * u(rng);
    for (double& x : q) x = std::clamp(centre + spread * u(rng), a, a + l);
    std::sort(q.begin(), q.end());
    clamp_cuts(q, a, a + l, mm);
    for (std::size_t k = 0; k < q.size(); ++k) {
      ASSERT_GE(q[k], a);
      ASSERT_LE(q[k], a + l);
      if (k > 0) {
        ASSERT_GE(q[k] - q[k - 1], mm) << trial;
      }
    }
    std::vector<double> again = q;
    clamp_cuts(again, a, a + l, mm);
    ASSERT_EQ(again, q);
  }
}

TEST(QuantileCuts, ImbalanceRatioIsMaxOverMean) {
  EXPECT_DOUBLE_EQ(imbalance_ratio(400, 400, 4), 4.0);
  EXPECT_DOUBLE_EQ(imbalance_ratio(100, 400, 4), 1.0);
  EXPECT_DOUBLE_EQ(imbalance_ratio(0, 0, 4), 1.0);
}
