#include "coupling/run/run_schedule.h"

#include <algorithm>
#include <cmath>

namespace upgrain::coupling {

RunSchedule make_schedule(const dem::SceneConfig& scene, const std::optional<OutputOptions>& output) {
  RunSchedule s;
  s.total = static_cast<long>(std::llround(scene.end_time / scene.time_step));
  auto every = [&](double interval) {
    return interval > 0.0 ? std::max(1L, static_cast<long>(std::llround(interval / scene.time_step)))
                          : s.total;
  };
  s.series_every = every(output ? output->series_interval : 0.002);
  s.snapshot_every = every(output ? output->snapshot_interval : 0.0);
  if (output && output->grid_stress.enabled())
    s.evaluation_every =
        output->grid_stress.interval > 0.0 ? every(output->grid_stress.interval) : s.snapshot_every;
  s.releases = dem::wall_releases(scene.container);
  return s;
}

long rest_window_steps(const dem::SceneConfig& scene, double settling_times) {
  if (!scene.effects.gravity || scene.gravity <= 0.0 || settling_times <= 0.0) return 0;
  const double settling_time = std::sqrt(2.0 * scene.particles.largest_radius() / scene.gravity);
  return static_cast<long>(std::ceil(settling_times * settling_time / scene.time_step));
}

bool rest_held(long step, bool below, long window, ScheduleState& state) {
  if (!below) {
    state.below_rest_since = -1;
    return false;
  }
  if (state.below_rest_since < 0) state.below_rest_since = step;
  return step - state.below_rest_since >= window;
}

}  // namespace upgrain::coupling
