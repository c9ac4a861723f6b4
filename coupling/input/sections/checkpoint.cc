// The Checkpoint section: when checkpoints are written and how many are kept (docs/restart.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto checkpoint(Member m) {
  return at(&SceneInput::output, &OutputOptions::checkpoint, m);
}

}  // namespace

Section checkpoint_section() {
  return {
      "Checkpoint",
      {real("interval", checkpoint(&CheckpointOptions::interval), 0.0, 1e6, "s",
            "Simulated time between checkpoints in <Output/folder>/checkpoints/ (docs/restart.md); 0 = "
            "none on a schedule. The same steps in every run of the scene, so an interrupted run "
            "resumed from one ends with the bytes of one that was not."),
       real("wall interval", checkpoint(&CheckpointOptions::wall_interval), 0.0, 1e9, "s",
            "Wall-clock time between checkpoints (checked at the time-series rows; by --study femxdem after "
            "each converged load step); 0 = none. A run "
            "also writes one when it is asked to stop (SIGINT, SIGTERM, SIGHUP), then exits with 128 + "
            "the signal."),
       integer("keep", checkpoint(&CheckpointOptions::keep), 1, 1000, "-",
               "The newest checkpoints kept; older ones are removed.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
