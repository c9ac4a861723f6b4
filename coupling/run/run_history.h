#pragma once
// A run over its starts (docs/restart.md, "Timings"): a run stopped or killed and continued
// with `upgrain --restart` is one run in several segments. Its report and summary.json give
// the wall-clock time of all of them, say where it was resumed, and name the scene it was
// started with; a checkpoint carries this to the next segment.
#include <string>
#include <vector>

namespace upgrain::coupling {

struct RunHistory {
  // The scene of the first start as the log named it (its file, or the built-in default).
  std::string scene_source;
  // The wall-clock seconds the steps took up to here, over every segment: each segment's time
  // from its start to the checkpoint the next one resumed from. The work a stop or kill lost
  // after that checkpoint is not counted: the steps were taken again. NaN when a checkpoint
  // written before Upgrain kept it was resumed.
  double wall_seconds = 0.0;
  // The steps at which the run was resumed, in order (empty: never).
  std::vector<long> resumed_at;
};

}  // namespace upgrain::coupling
