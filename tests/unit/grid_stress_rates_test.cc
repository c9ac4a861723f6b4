// Objective stress rates per grid cell over outputs (upscale/strain/grid_stress_rates.h),
// against exact answers:
//   - a packing spinning rigidly with a cell stress co-rotating with it, sigma = Q sigma0 Q^T:
//     all four rates vanish up to the backward difference's error, which falls at first
//     order at the second output (two points) and at second order from the third on;
//   - a packing at rest with a stress quadratic in time: every rate is sigma_dot, exact to
//     round-off from the third output (eq. (10) is exact for quadratics), and the two-point
//     difference at the second output is the chord's slope;
//   - the first output has no rate, cells without particles carry L's reason, nothing NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <tuple>
#include <vector>

#include "dem/core/error.h"
#include "upscale/strain/grid_strain.h"
#include "upscale/strain/grid_stress_rates.h"
#include "upscale/strain/strain_measures.h"

using namespace upgrain::dem;
using namespace upgrain::upscale;

namespace {

constexpr StrainDefinition kBoth[] = {StrainDefinition::best_fit, StrainDefinition::tessellation};

// 2 x 2 x 1 cells 2 m from the origin, 40 random points in each except the last cell (empty).
struct Packing {
  RegularGrid grid;
  std::vector<GlobalId> id;
  std::vector<Vec3> x;
  int empty_cell = 3;
};

Packing make_packing() {
  Packing p;
  p.grid.lo = Vec3(1.3, 1.2, 0.8);
  p.grid.hi = p.grid.lo + Vec3(0.04, 0.04, 0.02);
  p.grid.n[0] = 2;
  p.grid.n[1] = 2;
  p.grid.n[2] = 1;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  const Vec3 h(0.02, 0.02, 0.02);
  for (int c = 0; c < p.grid.num_cells(); ++c) {
    if (c == p.empty_cell) continue;
    const Vec3 corner = p.grid.cell_centre(c) - 0.5 * h;
    for (int k = 0; k < 40; ++k) {
      p.x.push_back(corner + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(h));
      p.id.push_back(static_cast<GlobalId>(p.id.size() + 1));
    }
  }
  return p;
}

Mat3 stress0() {
  Mat3 s;
  s << -3.0, 0.4, -0.7, 0.4, -2.0, 0.3, -0.7, 0.3, -5.0;
  return 1e3 * s;
}

double max_norm(const std::vector<Mat3>& m, const std::vector<StrainReason>& reason) {
  double worst = 0.0;
  for (std::size_t c = 0; c < m.size(); ++c)
    if (reason[c] == StrainReason::valid) worst = std::max(worst, m[c].norm());
  return worst;
}

// The packing turned rigidly about its centre at rate omega, with the co-rotating stress in
// every cell, at outputs 0, h, 2h, 3h. Returns the largest |rate| / (|omega| |sigma0|) over
// the cells, per output (index 1: two points, 2 and 3: three points), for each rate.
struct Spin {
  std::vector<double> jaumann, green_naghdi, truesdell, oldroyd;
};

Spin spinning_packing(double h) {
  const Packing p = make_packing();
  const Vec3 omega = Vec3(0.3, -0.8, 1.1);
  const Vec3 centre = 0.5 * (p.grid.lo + p.grid.hi);
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  StressRateHistory history(StressFormula::bagi);
  const std::vector<Vec3> v0;
  Spin s;
  std::optional<GridStrain> previous;
  for (int k = 0; k <= 3; ++k) {
    const double t = k * h;
    const Mat3 q = Eigen::AngleAxisd(t * omega.norm(), omega.normalized()).matrix();
    std::vector<Vec3> x, v;
    for (const Vec3& X : p.x) {
      x.push_back(centre + q * (X - centre));
      v.push_back(omega.cross(x.back() - centre));
    }
    GridStrain g = grid_strain(ref, p.grid, {p.id, x, v}, {t, k}, {}, previous ? &*previous : nullptr);
    const std::vector<Mat3> stress(static_cast<std::size_t>(p.grid.num_cells()),
                                   q * stress0() * q.transpose());
    const GridStressRates r = history.push(stress, g);
    EXPECT_EQ(r.outputs_used, std::min(k + 1, 3));
    const double scale = omega.norm() * stress0().norm();
    double j = 0, gn = 0, tr = 0, ol = 0;
    for (StrainDefinition d : kBoth) {
      const CellStressRates& f = r[d];
      for (int c = 0; c < p.grid.num_cells(); ++c) {
        for (const Mat3* m :
             {&f.stress_rate[c], &f.jaumann[c], &f.green_naghdi[c], &f.truesdell[c], &f.oldroyd[c]})
          EXPECT_TRUE(m->allFinite());
        if (k == 0) {
          EXPECT_EQ(f.reason[c], StrainReason::no_history);
          EXPECT_EQ(f.jaumann[c], Mat3::Zero());
        } else if (c == p.empty_cell) {
          EXPECT_EQ(f.reason[c], StrainReason::too_few_particles);
          EXPECT_EQ(f.green_naghdi_reason[c], StrainReason::too_few_particles);
          EXPECT_EQ(f.oldroyd[c], Mat3::Zero());
        } else {
          EXPECT_EQ(f.reason[c], StrainReason::valid);
          EXPECT_EQ(f.green_naghdi_reason[c], StrainReason::valid);
        }
      }
      j = std::max(j, max_norm(f.jaumann, f.reason) / scale);
      gn = std::max(gn, max_norm(f.green_naghdi, f.green_naghdi_reason) / scale);
      tr = std::max(tr, max_norm(f.truesdell, f.reason) / scale);
      ol = std::max(ol, max_norm(f.oldroyd, f.reason) / scale);
      // The rate is not trivially zero: sigma_dot is of size |omega| |sigma0|.
      if (k > 0) {
        EXPECT_GT(max_norm(f.stress_rate, f.reason) / scale, 0.1);
      }
    }
    s.jaumann.push_back(j);
    s.green_naghdi.push_back(gn);
    s.truesdell.push_back(tr);
    s.oldroyd.push_back(ol);
    previous = std::move(g);
  }
  return s;
}

}  // namespace

TEST(GridStressRates, CoRotatingStressHasZeroRatesAtTheBackwardDifferencesOrder) {
  const Spin coarse = spinning_packing(0.05), fine = spinning_packing(0.025);
  for (const auto& [name, a, b] : {std::tuple{"Jaumann", coarse.jaumann, fine.jaumann},
                                   std::tuple{"Green-Naghdi", coarse.green_naghdi, fine.green_naghdi},
                                   std::tuple{"Truesdell", coarse.truesdell, fine.truesdell},
                                   std::tuple{"Oldroyd", coarse.oldroyd, fine.oldroyd}}) {
    // Small against the size of sigma_dot, and converging at the order of the difference.
    const double order2 = std::log2(a[1] / b[1]);
    EXPECT_NEAR(order2, 1.0, 0.1) << name << " at the second output (two points)";
    for (int k : {2, 3}) {
      EXPECT_LT(a[k], 0.01) << name;
      EXPECT_NEAR(std::log2(a[k] / b[k]), 2.0, 0.15) << name << " at output " << k;
    }
    std::printf("%-12s rate/(|w||s0|) h = 0.05: %.2e %.2e %.2e; h = 0.025: %.2e %.2e %.2e\n", name, a[1],
                a[2], a[3], b[1], b[2], b[3]);
  }
}

TEST(GridStressRates, StressQuadraticInTimeAtRestGivesItsExactDerivative) {
  const Packing p = make_packing();
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  const std::vector<Vec3> v(p.x.size(), Vec3::Zero());
  Mat3 b, c;
  b << 1.0, 2.0, 0.5, 2.0, -1.0, 0.0, 0.5, 0.0, 3.0;
  c << -4.0, 1.0, 0.0, 1.0, 2.0, -1.5, 0.0, -1.5, 1.0;
  auto sigma = [&](double t) -> Mat3 { return stress0() + 1e3 * (t * b + t * t * c); };
  const double times[] = {0.0, 0.1, 0.25, 0.31};  // uneven outputs
  StressRateHistory history(StressFormula::weber);
  for (int k = 0; k < 4; ++k) {
    const GridStrain g = grid_strain(ref, p.grid, {p.id, p.x, v}, {times[k], k}, {});
    const std::vector<Mat3> stress(static_cast<std::size_t>(p.grid.num_cells()), sigma(times[k]));
    const GridStressRates r = history.push(stress, g);
    EXPECT_EQ(r.formula, StressFormula::weber);
    EXPECT_EQ(r.order(), std::min(k, 2));
    if (k == 0) continue;
    const Mat3 exact = k == 1 ? Mat3((sigma(times[1]) - sigma(times[0])) / (times[1] - times[0]))
                              : Mat3(1e3 * (b + 2.0 * times[k] * c));
    for (StrainDefinition d : kBoth)
      for (int cell = 0; cell < p.grid.num_cells(); ++cell) {
        if (cell == p.empty_cell) continue;
        const CellStressRates& f = r[d];
        ASSERT_EQ(f.reason[cell], StrainReason::valid);
        // L = 0 and R = 1: every rate is sigma_dot.
        for (const Mat3* m : {&f.stress_rate[cell], &f.jaumann[cell], &f.green_naghdi[cell],
                              &f.truesdell[cell], &f.oldroyd[cell]})
          EXPECT_LE((*m - exact).norm(), 1e-9 * exact.norm()) << "output " << k << " cell " << cell;
      }
  }
}

TEST(GridStressRates, MismatchedGridsAndTimesAreRefused) {
  const Packing p = make_packing();
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  const std::vector<Vec3> v(p.x.size(), Vec3::Zero());
  StressRateHistory history(StressFormula::bagi);
  const GridStrain g = grid_strain(ref, p.grid, {p.id, p.x, v}, {0.1, 1}, {});
  EXPECT_THROW((void)history.push(std::vector<Mat3>(3, Mat3::Zero()), g), upgrain::Error);
  (void)history.push(std::vector<Mat3>(4, Mat3::Zero()), g);
  EXPECT_THROW((void)history.push(std::vector<Mat3>(4, Mat3::Zero()), g), upgrain::Error);  // same time
  // A NaN stress is reported, not propagated.
  const GridStrain later = grid_strain(ref, p.grid, {p.id, p.x, v}, {0.2, 2}, {});
  std::vector<Mat3> bad(4, Mat3::Zero());
  bad[0](1, 2) = std::nan("");
  const GridStressRates r = history.push(bad, later);
  EXPECT_EQ(r[StrainDefinition::best_fit].reason[0], StrainReason::non_finite);
  EXPECT_TRUE(r[StrainDefinition::best_fit].jaumann[0].allFinite());
  EXPECT_EQ(r[StrainDefinition::best_fit].reason[1], StrainReason::valid);
}
