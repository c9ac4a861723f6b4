#pragma once
// When a run does what, in steps of the scene's time step: time-series rows, snapshots,
// grid evaluations (stress and strain) and the removal of walls (docs/output.md,
// docs/scenes.md). Plain numbers, so that the run loop and a checkpoint share them.
#include <optional>
#include <vector>

#include "coupling/run/output_options.h"
#include "dem/boundary/wall_release.h"
#include "dem/scene/scene_config.h"

namespace upgrain::coupling {

struct RunSchedule {
  long total = 0;             // steps to the end time
  long series_every = 1;      // time-series rows (and the test for rest)
  long snapshot_every = 1;    // snapshots
  long evaluation_every = 0;  // grid stress and strain; 0: none
  std::vector<dem::WallRelease> releases;

  [[nodiscard]] bool series_due(long s) const { return s % series_every == 0 || s == total; }
  [[nodiscard]] bool snapshot_due(long s) const { return s % snapshot_every == 0 || s == total; }
  [[nodiscard]] bool evaluation_due(long s) const {
    return evaluation_every > 0 && (s % evaluation_every == 0 || s == total);
  }
};

// The schedule of `scene` with `output` (without output: only the rows of the test for rest,
// every 2 ms of simulated time). An interval of 0 means once, at the end; a grid-stress
// interval of 0 means at each snapshot.
RunSchedule make_schedule(const dem::SceneConfig& scene, const std::optional<OutputOptions>& output);

// Where a run stands in its schedule: the steps done, the releases done, the first step
// after which the bed may be found at rest, and the step from which its kinetic energy has
// stayed below the rest ratio (-1: not below at the last row).
struct ScheduleState {
  long step = 0;
  std::size_t next_release = 0;
  long rest_check_from = 0;
  long below_rest_since = -1;
};

// The rest window in steps: `settling_times` times sqrt(d/g), d the largest grain's
// diameter, g gravity (docs/scenes.md, "Stopping at rest"); 0 without gravity.
long rest_window_steps(const dem::SceneConfig& scene, double settling_times);

// The test for rest at a time-series row of step `step`: `below` says whether the kinetic
// energy is below the rest ratio there. The bed is at rest once it has stayed below at every
// row for `window` steps; a row above starts the window again. A short lull, as when a
// deposition's grains are between bounces, does not stop the run.
bool rest_held(long step, bool below, long window, ScheduleState& state);

}  // namespace upgrain::coupling
