#pragma once
// Objective stress rates per grid cell over a run (docs/strain.md "Stress rates
// over time"): at each output the Jaumann, Green-Naghdi, Truesdell and Oldroyd rates
// (objective_rates.h, eq. (9)) of each cell from
//   - sigma: the cell's grid stress of one formula at this and the earlier outputs,
//   - L (Jaumann: W = skew L; Truesdell, Oldroyd) of the cell at this output,
//   - R of the polar decomposition of the cell's total F at the outputs differenced
//     (Green-Naghdi: Omega = skew(R_dot R^T)).
//
// Time differencing. The run writes each output as it goes, so sigma_dot (and R_dot) at
// output k is the one-sided BACKWARD difference over the outputs k-2, k-1, k: the "last
// output" formula of eq. (10), second order on any spacing, leading error
// -h2 (h1 + h2) sigma''' / 6 (-h^2 sigma'''/3 for even spacing, twice a central
// difference's). At the second output only two are available: the two-point difference,
// first order. At the first output (the reference) there is no rate: reason no_history.
//
// The stress is that of the grid cell (a fixed place when Stress/box is fixed), so
// sigma_dot is the rate at the cell, d sigma/dt, not the material derivative: the
// convective term v . grad sigma is left out. With an Eulerian strain set the stress, L and
// F all belong to the material in the cell now; with a Lagrangian set L and F belong to the
// material that was in the cell at t0.
//
// Nothing is NaN: a cell whose rate cannot be had is zero with a StrainReason.
#include <array>
#include <deque>
#include <span>
#include <vector>

#include "dem/core/types.h"
#include "dem/stress/stress_formula.h"
#include "upscale/strain/grid_strain.h"

namespace upgrain::upscale {

using dem::GridStress;
using dem::Mat3;
using dem::StressFormula;

// One definition's rates (the definition gives L and R), one entry per cell.
struct CellStressRates {
  std::vector<Mat3> stress_rate;  // sigma_dot by the backward difference
  std::vector<Mat3> jaumann;
  std::vector<Mat3> green_naghdi;
  std::vector<Mat3> truesdell;
  std::vector<Mat3> oldroyd;
  // sigma_dot, Jaumann, Truesdell, Oldroyd: L's reason when L is not valid, non_finite for a
  // non-finite stress, no_history at the first output.
  std::vector<StrainReason> reason;
  // Green-Naghdi besides: F's reason when F is not valid now, previous_invalid when it was
  // not valid at an output differenced.
  std::vector<StrainReason> green_naghdi_reason;

  void resize(int cells);
};

struct GridStressRates {
  StressFormula formula = StressFormula::bagi;
  int outputs_used = 0;  // 1: none (first output), 2: first order, 3: second order
  std::array<bool, kStrainDefinitionCount> computed = {false, false};
  std::array<CellStressRates, kStrainDefinitionCount> fields;
  std::vector<Mat3> stress;  // the cell stress used, at this output

  [[nodiscard]] int order() const { return outputs_used - 1; }
  [[nodiscard]] const CellStressRates& operator[](StrainDefinition d) const {
    return fields[static_cast<int>(d)];
  }
};

// Keeps the last three outputs (time, stress, each definition's R and F validity) and gives
// the rates at each new one.
class StressRateHistory {
 public:
  explicit StressRateHistory(StressFormula formula) : formula_(formula) {}

  // `stress` is the formula's cell stress on the grid of `strain` (same cell count), at the
  // time of `strain`, which must be later than the previous output's. Throws
  // upgrain::Error when the cell counts or times do not fit.
  GridStressRates push(std::span<const Mat3> stress, const GridStrain& strain);

  // The outputs kept, oldest first (for a checkpoint), and back.
  struct Output {
    double time = 0.0;
    std::vector<Mat3> stress;
    std::array<std::vector<Mat3>, kStrainDefinitionCount> rotation;
    std::array<std::vector<StrainReason>, kStrainDefinitionCount> f_reason;
  };
  [[nodiscard]] const std::deque<Output>& outputs() const { return outputs_; }
  [[nodiscard]] StressFormula formula() const { return formula_; }
  void restore(std::deque<Output> outputs) { outputs_ = std::move(outputs); }

 private:
  StressFormula formula_;
  std::deque<Output> outputs_;
};

}  // namespace upgrain::upscale
