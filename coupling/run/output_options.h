#pragma once
// What a run writes into its output folder and how often (docs/output.md): the snapshots and
// time series of the DEM (dem/io/run_recorder.h), the grid stress (dem/io/grid_stress_output.h)
// and the grid strain of the upscaling layer (upscale/strain/grid_strain_output.h).
#include <filesystem>
#include <string>
#include <vector>

#include "coupling/run/cg_capture.h"
#include "dem/io/grid_stress_output.h"
#include "dem/scene/effect_choice.h"
#include "upscale/strain/grid_strain_output.h"

namespace upgrain::coupling {

// Checkpoints (docs/restart.md): written into <folder>/checkpoints/ at an interval of simulated
// time, of wall-clock time, and when the run is asked to stop (SIGINT, SIGTERM, SIGHUP).
struct CheckpointOptions {
  double interval = 0.0;         // s of simulated time; 0: none on a schedule
  double wall_interval = 600.0;  // s of wall-clock time; 0: none
  int keep = 2;                  // the newest kept; older ones are removed
  // The scene's parameters as the driver read them (every entry, one per line), stored with
  // their hash so that a restart continues the same scene.
  std::string scene;
  // The scene's name as the log gives it (SceneInput::source): a restarted run's report names
  // the scene it was started with (run_history.h).
  std::string source;
};

struct OutputOptions {
  std::filesystem::path folder = "upgrain-output";
  double snapshot_interval = 0.05;  // s of simulated time; 0 = only first and last
  double series_interval = 0.002;   // s of simulated time between time-series rows
  dem::io::GridStressOptions grid_stress;
  upscale::GridStrainOutputOptions grid_strain;
  // Output/energy balance: elastic energy and dissipation in the time series and summary
  // (without it, the scene's effects leave energy tracking out, dem/scene/effect_choice.h).
  bool energy_balance = true;
  // The effect set and its reasons, for summary.json; empty: the scene's set as given.
  std::vector<dem::EffectChoice> effect_choices;
  CheckpointOptions checkpoint;
  // Output/force network: every contact with each snapshot after the first
  // (force_network/contacts_<step>.h5, force_network.xdmf; dem/io/force_network.h).
  bool force_network = false;
  // The states kept for the coarse-grained fields (docs/coarse-graining.md).
  CoarseGrainingCapture coarse_graining;
};

}  // namespace upgrain::coupling
