#pragma once
// The grid evaluations of a run (docs/stress.md, docs/strain.md): at each evaluation step, the
// stress of the fixed grid and of the compute grids (the MPI blocks), and, when asked for, the
// finite strain of both against their reference state and the objective stress rates of the
// fixed grid's cells. Written by rank 0; the stress is collective (dem/engine/simulation.h).
#include <optional>
#include <string>
#include <vector>

#include "coupling/run/output_options.h"
#include "dem/engine/simulation.h"
#include "dem/io/compute_grid_stress_output.h"
#include "dem/io/csv_series.h"
#include "dem/io/grid_stress_output.h"
#include "upscale/strain/grid_strain.h"
#include "upscale/strain/grid_strain_output.h"
#include "upscale/strain/grid_stress_rates.h"

namespace upgrain::coupling {

// What a checkpoint keeps of the grid evaluations (rank 0's): the files written and the rows
// of their tables, the strain references, the last strains (the next increment's F_prev) and
// the stresses the rates difference. A table not begun yet has -1 rows.
struct GridEvaluationState {
  std::vector<dem::io::GridStressEntry> stress_files;
  long stress_rows = 0;
  long compute_grid_rows = -1;
  std::vector<upscale::GridStrainEntry> strain_files;
  long strain_rows = 0;
  std::optional<upscale::StrainReference> reference;
  std::optional<upscale::GridStrain> previous;
  std::optional<upscale::StressRateHistory> rates;
  std::optional<upscale::StrainReference> block_reference;
  std::vector<dem::Box> reference_blocks;
  std::optional<upscale::GridStrain> previous_blocks;
  long block_rows = -1;
  long cell_rows = -1;  // cell_deformation.csv (a deforming cell's)
};

class GridEvaluation {
 public:
  // Collective. Opens the output files on rank 0; with a strain reference at t0 = 0, the
  // initial state is the reference and the first strain output (F = 1). With `resume` (read on
  // rank 0), a restart: the files and tables are cut back to the checkpoint's and the state is
  // its; nothing is evaluated.
  GridEvaluation(dem::Simulation& sim, const OutputOptions& output,
                 const GridEvaluationState* resume = nullptr);

  // Rank 0's state, for a checkpoint (not collective).
  [[nodiscard]] GridEvaluationState state() const;

  // Collective, after a step that recorded its contacts (Simulation::request_contacts()).
  void evaluate(dem::Simulation& sim);

  // The last evaluation: its grid and stress (every rank), its strain (rank 0).
  [[nodiscard]] const std::optional<dem::GridStress>& final_stress() const { return final_stress_; }
  [[nodiscard]] const dem::RegularGrid& final_grid() const { return final_grid_; }
  [[nodiscard]] const std::optional<upscale::GridStrain>& final_strain() const { return final_strain_; }

 private:
  // The grid of an evaluation, the same on every rank (a moving grid follows the whole
  // assembly, which rank 0 holds).
  [[nodiscard]] dem::RegularGrid grid_now(dem::Simulation& sim) const;
  // The strain of the fixed grid (with the stress rates when `stress` is given) and of the
  // compute grids; nothing before the reference time.
  void evaluate_strain(dem::Simulation& sim, const dem::RegularGrid& grid, const dem::GridStress* stress);
  void evaluate_block_strain(dem::Simulation& sim, const dem::ParticleStore& p,
                             const std::vector<int>& owner);
  void restore(const GridEvaluationState& s, int blocks);

  const OutputOptions& output_;
  bool strain_on_ = false;
  std::optional<dem::io::GridStressRecorder> stress_out_;
  std::optional<dem::io::ComputeGridStressRecorder> compute_grid_out_;  // per block
  std::optional<dem::GridStress> final_stress_;
  dem::RegularGrid final_grid_;

  // Strain of the fixed grid: the reference state (positions by global id at t0) kept on
  // rank 0, and the last outputs' stress for the objective rates (backward differences).
  std::optional<upscale::GridStrainRecorder> strain_out_;
  std::optional<upscale::StrainReference> strain_reference_;
  std::optional<upscale::StressRateHistory> rate_history_;
  std::optional<upscale::GridStrain> final_strain_;
  // MPI runs: the same strain per compute grid, the sets by owner rank at t0 (Lagrangian) or
  // now (Eulerian); no stress rates there, since a block's stress is neither that of a fixed
  // place nor of fixed material (docs/strain.md, "Compute grids").
  std::optional<upscale::ComputeGridStrainRecorder> block_strain_out_;
  std::optional<upscale::StrainReference> block_reference_;
  std::optional<dem::io::CsvSeries> cell_out_;  // a deforming cell's F beside its grains'
  std::vector<dem::Box> reference_blocks_;
  std::optional<upscale::GridStrain> last_block_strain_;
};

}  // namespace upgrain::coupling
