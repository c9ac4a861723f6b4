#pragma once
// What report.md says of a run over its segments (docs/restart.md, "Timings"): the scene it was
// started with, and its wall clock, on one line of its own that begins "- Wall clock:" (the
// restart tests compare reports without it, as the timings of every other run differ too).
#include <string>

#include "coupling/input/scene_input.h"
#include "coupling/run/run_result.h"

namespace upgrain::coupling {

// The scene the run was started with (a restart's own command when the checkpoint did not
// keep it).
std::string scene_source(const SceneInput& in, const RunResult& r);

// "- Wall clock: ..." with its newline: the time of every segment, where the run was resumed
// and this segment's time.
std::string wall_clock_line(const RunResult& r);

}  // namespace upgrain::coupling
