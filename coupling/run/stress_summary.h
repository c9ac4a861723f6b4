#pragma once
// The final grid stress of one formula in two figures for the driver's log: the largest
// relative asymmetry index (Yan and Regueiro eq. 20, dem/stress/asymmetry.h, docs/stress.md) and the mean
// sigma_zz of the bottom layer of cells. A cell with a grain in it but next to no stress (a grain resting in
// it alone, 1e-89 Pa of round-off) has an RAI of round-off over round-off, up to infinity:
// such cells are counted apart instead of ruling the largest RAI.
#include "dem/stress/grid_stress.h"

namespace upgrain::coupling {

struct StressSummary {
  double max_rai = 0.0;      // over the rated cells; a fraction, infinite when only skew stress
  int rated_cells = 0;       // cells with grains and a measurable stress
  int negligible_cells = 0;  // cells with grains whose stress is below kNegligibleStress of the largest
  double floor_szz = 0.0;    // mean sigma_zz of the bottom layer's cells with grains (Pa)
};

// A cell's stress norm below this fraction of the grid's largest (of any formula) is round-off.
inline constexpr double kNegligibleStress = 1e-9;

StressSummary summarise_stress(const dem::GridStress& g, const dem::RegularGrid& grid, dem::StressFormula f);

}  // namespace upgrain::coupling
