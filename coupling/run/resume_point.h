#pragma once
// Where a restart may continue a run (docs/restart.md, "What a restart does", "What is
// refused"). Two rules, both about the end step of the restarted run:
// - It may not lie before the checkpoint: the run goes on from the checkpoint's state, and its
//   files up to there are the run's; an end time before it is refused, naming the file, the
//   entry and the checkpoint's time.
// - A restart takes at least one step. The end of a run (report.md, summary.json, the strain on
//   the mesh, a study's continua) is made from what its last step left in memory: the grid
//   evaluation's stress and strain measures, the contacts it recorded. A checkpoint holds what
//   the next step needs, not that; a restart from a checkpoint at the end step ended with the
//   strain measures zero. It continues from the newest checkpoint before the end step instead.
//   A run that relaxes at its end may resume at its own end step: the relaxation and its
//   recorded step make the end's figures again.
#include <string>

#include "dem/scene/scene_config.h"

namespace upgrain::coupling {

// The step a run of `scene` ends at (its schedule's count, run_schedule.h).
long end_step(const dem::SceneConfig& scene);

// Throws upgrain::Error, one line, when `end_time` (Simulation/end time of `source`, a run's
// end at step `end`) lies before the checkpoint `checkpoint` at `step`, `time`.
void refuse_end_before(const std::string& source, double end_time, long end, const std::string& checkpoint,
                       long step, double time);

// Whether a restart to step `end` may continue from a checkpoint at `step`, whose own run ended
// at `checkpoint_end` (the end time stored in it); `relaxes`: the run relaxes at its end.
bool may_continue_from(long step, long end, long checkpoint_end, bool relaxes);

}  // namespace upgrain::coupling
