#pragma once
// What a run leaves in its output folder: HDF5 snapshots with an XDMF companion, a CSV
// time series of energies and contacts, and a JSON summary. Every file is written
// atomically; the time series is appended to at each snapshot (csv_series.h).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "dem/boundary/container.h"
#include "dem/engine/diagnostics.h"
#include "dem/engine/energy.h"
#include "dem/io/csv_series.h"
#include "dem/io/hdf5_snapshot.h"
#include "dem/scene/effect_choice.h"
#include "dem/strain/grid_strain.h"
#include "dem/stress/grid_stress.h"

namespace upgrain::dem::io {

// Which grid stress a run writes (docs/stress.md). No formulas: none.
struct GridStressOptions {
  std::vector<StressFormula> formulas;
  int cells[3] = {3, 3, 4};
  // The grid's box; when not set: the container's footprint, from the floor to the top of
  // the highest grain at each evaluation (the grid follows the assembly as it settles).
  bool fixed_box = false;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  double interval = 0.0;  // s of simulated time between evaluations; 0 = at each snapshot

  [[nodiscard]] bool enabled() const { return !formulas.empty(); }
};

// The grid of one evaluation: the fixed box, or the container footprint up to the top of
// the highest grain (for the unconstrained collapse, widened to the grains' extent).
RegularGrid stress_grid(const GridStressOptions& options, const ParticleStore& p, const BoxContainer& box);

// Which grid strain a run writes (docs/strain.md). Evaluated with the grid stress, on its
// grid (Stress/grid cells and box), so it needs the grid stress enabled.
struct GridStrainOutputOptions {
  bool enabled = false;
  // t0 (s): the reference state is the initial state when 0, otherwise the first grid-stress
  // evaluation at or after t0. No strain is written before it.
  double reference_time = 0.0;
  GridStrainOptions kernel;  // set (Lagrangian or Eulerian) and definitions
  // The grid-stress formula whose cell series gives the objective stress rates written with
  // the strain (dem/strain/grid_stress_rates.h); it must be among the formulas written.
  StressFormula rate_formula = StressFormula::bagi;
};

struct OutputOptions {
  std::filesystem::path folder = "upgrain-output";
  double snapshot_interval = 0.05;  // s of simulated time; 0 = only first and last
  double series_interval = 0.005;   // s of simulated time between time-series rows
  GridStressOptions grid_stress;
  GridStrainOutputOptions grid_strain;
  // Output/energy balance: elastic energy and dissipation in the time series and summary
  // (without it, the scene's effects leave energy tracking out, dem/scene/effect_choice.h).
  bool energy_balance = true;
  // The effect set and its reasons, for summary.json; empty: the scene's set as given.
  std::vector<EffectChoice> effect_choices;
};

class RunRecorder {
 public:
  // Creates the folder (and its snapshots/ subfolder).
  explicit RunRecorder(OutputOptions options);

  // One row of the time series, and a snapshot of a whole state sorted by id.
  void record_series(double time, long step, const EnergyBalance& e, double balance_error,
                     const StepDiagnostics& d);
  void write_snapshot(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                      const std::vector<Vec3>& wall_forces, double time, long step);
  // Appends the new rows to time_series.csv and rewrites particles.xdmf.
  void flush();
  void write_summary(const std::map<std::string, std::string>& entries) const;

  [[nodiscard]] const OutputOptions& options() const { return options_; }
  [[nodiscard]] const std::vector<std::string>& series_rows() const { return rows_; }

 private:
  OutputOptions options_;
  std::vector<std::string> rows_;
  std::size_t rows_written_ = 0;
  CsvSeries series_;
  std::vector<SnapshotInfo> snapshots_;
};

}  // namespace upgrain::dem::io
