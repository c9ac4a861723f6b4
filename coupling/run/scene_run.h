#pragma once
// The run of a scene, whatever it is (a deposition, a collapse, a settled bed carried on):
// fill the container, step to the end time or until the bed is at rest, remove walls at their
// time, write the time series, snapshots and grid evaluations on schedule, relax at the end
// if asked, write checkpoints and stop cleanly when asked to (docs/restart.md), and summarise
// (docs/output.md, docs/scenes.md). Used by the driver, the studies
// and the regression tests; collective over the engine's ranks.
#include <mpi.h>

#include <functional>
#include <optional>

#include "coupling/run/checkpoint.h"
#include "coupling/run/lid.h"
#include "coupling/run/output_options.h"
#include "coupling/run/progress_clock.h"
#include "coupling/run/run_result.h"
#include "dem/engine/relaxation.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

struct RunControl {
  // Stop early once kinetic energy < rest_ratio * (potential energy released) at every
  // time-series row for rest_window settling times sqrt(d/g) (run_schedule.h, rest_held),
  // after the first tenth of the run; a rest ratio of 0 disables.
  double rest_ratio = 0.0;
  double rest_window = 2.0;
  // After the run, relax the bed to static equilibrium by FIRE (dem/engine/relaxation.h) and
  // write the final snapshot and grid stress of the relaxed state.
  bool relax_at_end = false;
  dem::RelaxationOptions relaxation;
  // A lid placed on the bed and driven or servo-controlled (lid.h). A run with a lid does not
  // stop at rest, and a relaxation at the end holds the lid still.
  LidControl lid;
  // Keep the engine's final state in RunResult::final_state (rank 0's): a study's calibration
  // loads the bed it compares (docs/study.md).
  bool keep_final_state = false;
  // Keep the side-wall contacts of the last recorded step in RunResult::side_wall_contacts
  // (rank 0's): the study's wall shear against height.
  bool keep_wall_contacts = false;
};

// The scene's fill, made on rank 0 (empty on the others); collective: a fill that fails fails
// on every rank.
dem::ParticleStore fill_on_root(const dem::SceneConfig& scene, MPI_Comm comm);

// From the scene's fill (made on rank 0), collective over `comm`: every rank keeps the grains
// of its block. The output is written by rank 0 and holds the same bytes on any rank count
// with deterministic summation (docs/parallel.md, "Runs from the driver"); the result is
// complete on rank 0 only (bed, mass, strain and progress reports are rank 0's; the other
// fields are the same on every rank).
RunResult run_scene(const dem::SceneConfig& scene, const RunControl& control,
                    const std::optional<OutputOptions>& output, const ProgressReport& on_progress = {},
                    MPI_Comm comm = MPI_COMM_SELF, const dem::EngineOptions& options = {});

// The same on an engine already made (collective over its ranks).
RunResult run_scene(dem::Simulation& engine, const RunControl& control,
                    const std::optional<OutputOptions>& output, const ProgressReport& on_progress = {});

// Continues a run from a checkpoint (docs/restart.md; `checkpoint` is read on rank 0) in its own
// output folder, on any number of ranks: the tables are cut back to the checkpoint's rows, files
// written after it are removed, and the run goes on from the step after it. `scene` and
// `output` are the run's (from the checkpoint's parameters). With the deterministic summation it
// ends with the bytes of the run that was not interrupted.
RunResult resume_scene(const dem::SceneConfig& scene, const Checkpoint& checkpoint, const RunControl& control,
                       const OutputOptions& output, const ProgressReport& on_progress = {},
                       MPI_Comm comm = MPI_COMM_SELF, const dem::EngineOptions& options = {});

}  // namespace upgrain::coupling
