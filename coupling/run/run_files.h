#pragma once
// The DEM's own files of a run (dem/io/run_recorder.h): a time-series row and summary.json,
// written by rank 0, and a snapshot of the whole state (with its force network) on demand,
// written by every rank. Without output
// options, nothing is written and the calls do nothing. Collective over the engine's ranks.
#include <optional>

#include "coupling/run/output_options.h"
#include "coupling/run/run_result.h"
#include "dem/engine/simulation.h"
#include "dem/io/force_network.h"
#include "dem/io/run_recorder.h"

namespace upgrain::coupling {

class RunFiles {
 public:
  RunFiles(dem::Simulation& sim, const std::optional<OutputOptions>& output);

  [[nodiscard]] bool enabled() const { return output_.has_value(); }
  // A row of time_series.csv (energies, balance error, contacts) and the rows of walls.csv.
  void record_series(dem::Simulation& sim);
  // snapshots/particles_<step>.h5 of the checked whole state, with the wall forces; with
  // Output/force network, the contacts of the step when it recorded them (request_contacts()).
  void write_snapshot(dem::Simulation& sim);
  // Whether the step before a snapshot must record its contacts (for the force network).
  [[nodiscard]] bool wants_contacts() const { return output_ && output_->force_network; }
  // The last rows and summary.json.
  void write_summary(const dem::Simulation& sim, const RunResult& r);

  // A checkpoint's part (rank 0, after a flush): the series rows and the snapshots so far;
  // and a restart from it (collective; `s` is read on rank 0).
  [[nodiscard]] dem::io::RunRecorder::State state();
  void resume(dem::Simulation& sim, const dem::io::RunRecorder::State& s);

 private:
  const std::optional<OutputOptions>& output_;
  std::optional<dem::io::RunRecorder> recorder_;          // rank 0
  std::optional<dem::io::ForceNetworkRecorder> network_;  // with Output/force network
};

}  // namespace upgrain::coupling
