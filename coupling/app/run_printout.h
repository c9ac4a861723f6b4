#pragma once
// What the driver prints of a run on rank 0: its progress line and the summary of its DEM run.
#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// One line, rewritten in place; a new phase starts a new line. The time left is at the rate of
// the last seconds (coupling/run/progress_clock.h): a bound, not a promise, where the run may
// stop sooner at rest or at its relaxation tolerance.
void print_progress(const Progress& p);

// The DEM run's summary: steps, relaxation, bed, energy, load, ellipsoid contacts, the grid
// stress per formula and where the results are.
void print_deposition(const SceneInput& in, const RunResult& r);

}  // namespace upgrain::coupling
