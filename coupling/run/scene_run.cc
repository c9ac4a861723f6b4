#include "coupling/run/scene_run.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "coupling/run/grid_evaluation.h"
#include "coupling/run/run_files.h"
#include "coupling/run/run_schedule.h"
#include "dem/parallel/exchange.h"
#include "dem/scene/fill.h"

namespace upgrain::coupling {

namespace {

using Clock = std::chrono::steady_clock;

// Progress reports on rank 0, at most one a second and at the last step.
class ProgressClock {
 public:
  ProgressClock(const dem::Simulation& sim, const ProgressReport& report)
      : report_(sim.is_root() ? report : ProgressReport{}), start_(Clock::now()), last_(start_) {}

  void at(long s, long total, bool last) {
    if (!report_) return;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_).count() < 1.0 && s != total && !last) return;
    const double rate = s / std::max(seconds(), 1e-9);
    report_({s, total, rate, (total - s) / rate});
    last_ = now;
  }
  [[nodiscard]] double seconds() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }

 private:
  ProgressReport report_;
  Clock::time_point start_, last_;
};

// Walls taken out at their time (the collapse scenes, dem/boundary/wall_release.h). The bed is
// not "at rest" while a release is pending, nor in the first tenth of the time left after the
// last one: just after it the bed is still as still as it was behind the walls.
void release_walls(dem::Simulation& sim, const RunSchedule& schedule, ScheduleState& state) {
  while (state.next_release < schedule.releases.size() &&
         sim.time() >= schedule.releases[state.next_release].time) {
    for (const std::string& wall : schedule.releases[state.next_release].walls) sim.remove_wall(wall);
    ++state.next_release;
    state.rest_check_from = std::max(state.rest_check_from, state.step + (schedule.total - state.step) / 10);
  }
}

// One step, recorded when an evaluation is due, and its outputs.
struct StepOutputs {
  RunFiles& files;
  std::optional<GridEvaluation>& grids;

  // A recorded step of the final state (after the run stopped at rest between evaluations, or
  // after the relaxation): its stress, series row and snapshot.
  void final_step(dem::Simulation& sim) const {
    if (grids) sim.request_contacts();
    sim.step();
    if (grids) grids->evaluate(sim);
    files.record_series(sim);
    files.write_snapshot(sim);
  }
};

}  // namespace

RunResult run_scene(const dem::SceneConfig& scene, const RunControl& control,
                    const std::optional<OutputOptions>& output, const ProgressReport& on_progress,
                    MPI_Comm comm, const dem::EngineOptions& options) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  dem::ParticleStore fill;
  std::string error;
  if (rank == 0) {
    try {
      fill = dem::fill_container(scene);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  dem::throw_if_any(comm, error);
  dem::Simulation sim(scene, std::move(fill), comm, options);
  return run_scene(sim, control, output, on_progress);
}

RunResult run_scene(dem::Simulation& sim, const RunControl& control,
                    const std::optional<OutputOptions>& output, const ProgressReport& on_progress) {
  const RunSchedule schedule = make_schedule(sim.scene(), output);
  RunFiles files(sim, output);
  files.record_series(sim);
  files.write_snapshot(sim);
  // Grid stress needs the contacts of a force evaluation, which are recorded on request
  // before the step that computes them (Simulation::request_contacts()).
  std::optional<GridEvaluation> grids;
  if (schedule.evaluation_every > 0) grids.emplace(sim, *output);
  const StepOutputs outputs{files, grids};
  StateCapture states(output ? output->coarse_graining : CoarseGrainingCapture{});
  states.at_step(sim);

  RunResult r;
  ScheduleState state;
  state.rest_check_from = schedule.total / 10;
  ProgressClock clock(sim, on_progress);
  for (long s = 1; s <= schedule.total; ++s) {
    state.step = s;
    states.at_step(sim);
    release_walls(sim, schedule, state);
    const bool walls_pending = state.next_release < schedule.releases.size();
    const bool evaluate = schedule.evaluation_due(s);
    if (evaluate) sim.request_contacts();
    sim.step();
    if (evaluate) grids->evaluate(sim);
    const bool series_now = schedule.series_due(s);
    if (series_now) {
      files.record_series(sim);
      // Every rank takes the same decision: the energies are the same bits everywhere.
      if (control.rest_ratio > 0.0 && s > state.rest_check_from && !walls_pending &&
          sim.kinetic_to_released() < control.rest_ratio)
        r.stopped_at_rest = true;
    }
    if (files.enabled() && (schedule.snapshot_due(s) || r.stopped_at_rest)) {
      if (!series_now) files.record_series(sim);
      files.write_snapshot(sim);
    }
    clock.at(s, schedule.total, r.stopped_at_rest);
    if (r.stopped_at_rest) {
      // One more step, recorded, so that the final state has its stress.
      if (grids && !evaluate && !control.relax_at_end) outputs.final_step(sim);
      break;
    }
  }
  if (control.relax_at_end) {
    r.relaxation = dem::relax_to_equilibrium(sim, control.relaxation);
    // One recorded step of the relaxed state for its stress, snapshot and series row.
    outputs.final_step(sim);
  }
  measure_final_state(sim, clock.seconds(), r);
  if (grids) {
    r.final_stress = grids->final_stress();
    r.final_grid = grids->final_grid();
    r.final_strain = grids->final_strain();
  }
  // After the figures of the final state: a later state for differences moves the engine on.
  r.coarse_graining = states.at_end(sim);
  files.write_summary(sim, r);
  return r;
}

}  // namespace upgrain::coupling
