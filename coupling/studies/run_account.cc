#include "coupling/studies/run_account.h"

#include <cmath>

#include "coupling/studies/report_format.h"

namespace upgrain::coupling {

std::string scene_source(const SceneInput& in, const RunResult& r) {
  return r.history.scene_source.empty() ? in.source : r.history.scene_source;
}

std::string wall_clock_line(const RunResult& r) {
  const std::vector<long>& at = r.history.resumed_at;
  if (at.empty()) return "- Wall clock: " + fmt(r.wall_seconds, 3) + " s.\n";
  std::string steps;
  for (std::size_t k = 0; k < at.size(); ++k)
    steps += (k == 0 ? "" : k + 1 == at.size() ? " and " : ", ") + std::to_string(at[k]);
  const std::string resumed = "the run was resumed from its checkpoints at step" +
                              std::string(at.size() > 1 ? "s " : " ") + steps + " (docs/restart.md)";
  if (!std::isfinite(r.wall_seconds))
    return "- Wall clock: not known for the segments before step " + std::to_string(at.back()) +
           " (their checkpoint did not keep it); " + resumed + ", and this last segment took " +
           fmt(r.segment_seconds, 3) + " s.\n";
  return "- Wall clock: " + fmt(r.wall_seconds, 3) + " s over " + std::to_string(at.size() + 1) +
         " segments: " + resumed + ", and this last segment took " + fmt(r.segment_seconds, 3) +
         " s. Each earlier segment counts up to the checkpoint the next resumed from: the work a stop "
         "or kill lost after it is not counted.\n";
}

}  // namespace upgrain::coupling
