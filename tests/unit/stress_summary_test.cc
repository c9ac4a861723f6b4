// The driver's summary of a grid's final stress (coupling/run/stress_summary.h): a cell with a
// grain but round-off stress does not rule the largest relative asymmetry index.
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/run/stress_summary.h"
#include "dem/stress/asymmetry.h"

namespace upgrain::coupling {
namespace {

// A formula whose every cell is round-off (no contacts yet) against one that carries the
// grains' weight: nothing of it is rated.
TEST(StressSummary, AFormulaOfRoundOffAloneRatesNoCell) {
  dem::RegularGrid grid;
  dem::GridStress g;
  g.particles = {4};
  dem::Mat3 weight = dem::Mat3::Zero();
  weight(2, 2) = -0.3;
  dem::Mat3 noise = dem::Mat3::Zero();
  noise(0, 1) = 3e-90;
  g.sigma[static_cast<int>(dem::StressFormula::de_saxce)] = {weight};
  g.sigma[static_cast<int>(dem::StressFormula::weber)] = {noise};
  const StressSummary s = summarise_stress(g, grid, dem::StressFormula::weber);
  EXPECT_EQ(s.rated_cells, 0);
  EXPECT_EQ(s.negligible_cells, 1);
  EXPECT_EQ(summarise_stress(g, grid, dem::StressFormula::de_saxce).rated_cells, 1);
}

TEST(StressSummary, CellsOfRoundOffStressAreLeftOutOfTheLargestRai) {
  dem::RegularGrid grid;
  grid.n[0] = 2;  // two cells side by side, both in the bottom layer
  dem::GridStress g;
  g.particles = {3, 1};
  dem::Mat3 loaded;
  loaded << -100.0, 2.0, 0.0, 1.0, -100.0, 0.0, 0.0, 0.0, -1000.0;
  dem::Mat3 round_off = dem::Mat3::Zero();
  round_off(0, 1) = 1e-89;  // skew only: an RAI of infinity
  round_off(1, 0) = -1e-89;
  const auto f = dem::StressFormula::weber;
  g.sigma[static_cast<int>(f)] = {loaded, round_off};
  ASSERT_TRUE(std::isinf(dem::relative_asymmetry_index(round_off)));

  const StressSummary s = summarise_stress(g, grid, f);
  EXPECT_EQ(s.rated_cells, 1);
  EXPECT_EQ(s.negligible_cells, 1);
  EXPECT_EQ(s.max_rai, dem::relative_asymmetry_index(loaded));
  EXPECT_TRUE(std::isfinite(s.max_rai));
  EXPECT_EQ(s.floor_szz, 0.5 * (-1000.0 + 0.0));
}

TEST(StressSummary, ASkewOnlyCellWithRealStressStaysUnbounded) {
  dem::RegularGrid grid;
  dem::GridStress g;
  g.particles = {2};
  dem::Mat3 skew = dem::Mat3::Zero();
  skew(0, 1) = 5.0;
  skew(1, 0) = -5.0;
  const auto f = dem::StressFormula::bagi;
  g.sigma[static_cast<int>(f)] = {skew};
  EXPECT_TRUE(std::isinf(summarise_stress(g, grid, f).max_rai));
}

}  // namespace
}  // namespace upgrain::coupling
