#pragma once
// Stress per compute grid of an MPI run (the blocks of the decomposition, one per rank,
// as Yan and Regueiro compute it (docs/stress.md); dem/parallel/parallel_stress.h): compute_grid_stress.csv,
// a row per evaluation, block and formula, with the block's box (the outer blocks clipped to the
// decomposition box) and its volume V. The blocks depend on the rank count and move with the load balance,
// so, unlike the fixed grid, this table is not rank-independent.
#include <filesystem>
#include <string>
#include <vector>

#include "dem/io/csv_series.h"
#include "dem/stress/grid_stress.h"

namespace upgrain::dem::io {

class ComputeGridStressRecorder {
 public:
  ComputeGridStressRecorder(std::filesystem::path folder, std::vector<StressFormula> formulas);
  // Appends the rows of this evaluation.
  void record(const ComputeGridStress& blocks, double time, long step);
  [[nodiscard]] long csv_rows() const { return csv_.rows(); }
  void resume(long csv_rows) { csv_.resume(csv_rows); }

 private:
  std::filesystem::path folder_;
  std::vector<StressFormula> formulas_;
  CsvSeries csv_;
};

}  // namespace upgrain::dem::io
