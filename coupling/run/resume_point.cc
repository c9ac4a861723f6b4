#include "coupling/run/resume_point.h"

#include <cstdio>

#include "coupling/run/run_schedule.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

long end_step(const dem::SceneConfig& scene) { return make_schedule(scene, std::nullopt).total; }

void refuse_end_before(const std::string& source, double end_time, long end, const std::string& checkpoint,
                       long step, double time) {
  if (end >= step) return;
  char m[1024];
  std::snprintf(m, sizeof m,
                "%s: Simulation/end time = %.9g s is before the checkpoint the run would continue from, %s "
                "at t = %.9g s (step %ld): a restart goes on from there; give an end time of at least %.9g s",
                source.c_str(), end_time, checkpoint.c_str(), time, step, time);
  throw Error(m);
}

bool may_continue_from(long step, long end, long checkpoint_end, bool relaxes) {
  return step < end || (step == end && relaxes && checkpoint_end == step);
}

}  // namespace upgrain::coupling
