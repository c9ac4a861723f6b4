#pragma once
// Checkpoints of a run (docs/restart.md): the engine's whole state (dem/engine/engine_state.h)
// and where the run stands (its schedule, the files and table rows written, the grid
// evaluations' state), or a study's own state in their place (the FEM x DEM study's, docs/femxdem.md),
// with the scene's parameters and their hash, in one HDF5 file
// <folder>/checkpoints/checkpoint_<step>.h5, written atomically (temporary name, flushed, closed,
// stamped with a checksum of its bytes, synced, then renamed); the newest `keep` are kept. A
// restart reads the newest one that is valid.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "coupling/run/grid_evaluation.h"
#include "coupling/run/run_history.h"
#include "coupling/run/run_schedule.h"
#include "dem/engine/engine_state.h"
#include "dem/engine/pour.h"
#include "dem/io/run_recorder.h"
#include "upscale/cg/grain_state.h"

namespace upgrain::coupling {

// 2: the file begins with a checksum block (dem/io/checksum_block.h).
inline constexpr int kCheckpointVersion = 2;

// Where a run stands besides the engine.
struct RunState {
  ScheduleState schedule;
  dem::PourState pour;  // grains inserted and batches done (docs/insertion.md)
  dem::io::RunRecorder::State files;
  bool grids = false;  // the run evaluates grids
  GridEvaluationState grid_state;
  // The coarse-grained displacement's reference, once taken (docs/coarse-graining.md).
  std::optional<upscale::cg::ReferencePositions> cg_reference;
  // The segments before this checkpoint: wall time, resumes, the scene's name (run_history.h).
  RunHistory history;
};

// A study's own state in place of the engine's and the run's: named blocks of bytes that only the
// study reads (the FEM x DEM study: its solver's files and its tables so far).
struct StudyState {
  std::string study;  // as `upgrain --study` takes it
  std::vector<std::pair<std::string, std::vector<char>>> blocks;
  // The block named `name`; throws upgrain::Error naming the checkpoint when it has none.
  [[nodiscard]] const std::vector<char>& block(const std::string& name,
                                               const std::filesystem::path& file) const;
};

struct Checkpoint {
  std::filesystem::path file;
  long step = 0;
  double time = 0.0;
  std::string scene;  // the scene's parameters, one entry per line (CheckpointOptions::scene)
  std::string scene_hash;
  // The run whose folder it belongs to (docs/output.md, "Manifest"): its identity, and what its
  // manifest listed when the checkpoint was written, so that a restart removes what came after.
  // Taken from the open output journal by write_checkpoint; empty without one.
  std::string run_id;
  std::vector<std::string> outputs;
  dem::EngineState engine;
  RunState run;
  // A study's checkpoint: its state, and no engine or run state.
  std::optional<StudyState> study;
};

// The hash of a scene's parameter text (64-bit FNV-1a, in hex): the same text, the same hash.
std::string scene_hash(const std::string& scene);

// Writes `c` (its engine state and run state) as checkpoint_<step>.h5 in <folder>/checkpoints/,
// then removes all but the newest `keep`. Rank 0 only; throws upgrain::Error naming the file
// when it cannot be written whole (nothing is then left under the checkpoint's name).
std::filesystem::path write_checkpoint(const std::filesystem::path& folder, const Checkpoint& c, int keep);

// Every checkpoint file of <folder>/checkpoints/, newest (largest step) first.
std::vector<std::filesystem::path> checkpoint_files(const std::filesystem::path& folder);

// Reads one checkpoint; throws upgrain::Error naming the file and what is wrong (its bytes do
// not match its checksum, not HDF5, of another version, a part missing or out of range).
Checkpoint read_checkpoint(const std::filesystem::path& file);

// The newest checkpoint of `folder` that reads whole, of a step before `before_step` when it is
// given. Each newer one that does not read is named in `refused` ("checkpoint <file>:
// <reason>"). Throws upgrain::Error with the newest one's reason when none reads.
Checkpoint newest_checkpoint(const std::filesystem::path& folder, std::vector<std::string>& refused,
                             long before_step = -1);

}  // namespace upgrain::coupling
