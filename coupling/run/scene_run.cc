#include "coupling/run/scene_run.h"

#include <algorithm>
#include <chrono>
#include <regex>
#include <string>
#include <utility>

#include "coupling/run/checkpoint_clock.h"
#include "coupling/run/grid_evaluation.h"
#include "coupling/run/progress_clock.h"
#include "coupling/run/run_files.h"
#include "coupling/run/run_schedule.h"
#include "coupling/run/stop_request.h"
#include "dem/core/out_of_memory.h"
#include "dem/parallel/exchange.h"
#include "dem/scene/fill.h"

namespace upgrain::coupling {

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

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

// One run of the loop, fresh or resumed.
class SceneRun {
 public:
  SceneRun(dem::Simulation& sim, const RunControl& control, const std::optional<OutputOptions>& output,
           const ProgressReport& on_progress, const RunState* resume)
      : sim_(sim),
        control_(control),
        output_(output),
        schedule_(make_schedule(sim.scene(), output)),
        files_(sim, output),
        checkpoints_(output ? output->checkpoint : no_checkpoints_, sim.time_step(), output.has_value()),
        clock_(sim.is_root() ? on_progress : ProgressReport{}, resume ? resume->schedule.step : 0),
        states_(output ? output->coarse_graining : CoarseGrainingCapture{}),
        lid_(control.lid),
        pour_(sim.scene()),
        rest_window_(rest_window_steps(sim.scene(), control.rest_window)) {
    if (resume) {
      resume_history(resume->history, resume->schedule.step);
      files_.resume(sim, resume->files);
      states_.resume(sim, resume->cg_reference);
      if (schedule_.evaluation_every > 0)
        allocating("the stress and strain grids", [&] { grids_.emplace(sim, *output, &resume->grid_state); });
      // The schedule's state is rank 0's (the checkpoint is read there).
      long where[6] = {resume->schedule.step,
                       static_cast<long>(resume->schedule.next_release),
                       resume->schedule.rest_check_from,
                       resume->schedule.below_rest_since,
                       resume->pour.inserted,
                       resume->pour.batches};
      MPI_Bcast(where, 6, MPI_LONG, 0, sim.comm());
      state_ = {where[0], static_cast<std::size_t>(where[1]), where[2], where[3]};
      pour_ = dem::Pour(sim.scene(), {where[4], where[5]});
      clock_ = ProgressClock(sim.is_root() ? on_progress : ProgressReport{}, state_.step);
      keep_replay_start();
      return;
    }
    if (output) history_.scene_source = output->checkpoint.source;
    files_.record_series(sim);
    allocating("a snapshot (each rank's rows of the state; a force network's gathered on rank 0)",
               [&] { files_.write_snapshot(sim); });
    keep_replay_start();
    // Grid stress needs the contacts of a force evaluation, which are recorded on request
    // before the step that computes them (Simulation::request_contacts()).
    if (schedule_.evaluation_every > 0)
      allocating("the stress and strain grids", [&] { grids_.emplace(sim, *output); });
    state_.rest_check_from = schedule_.total / 10;
    states_.at_step(sim);
  }

  RunResult run() {
    RunResult r;
    first_step_ = sim_.step_count();
    for (long s = state_.step + 1; s <= schedule_.total; ++s) {
      state_.step = s;
      states_.at_step(sim_);
      controls_before_step(sim_, state_, lid_, pour_);
      // Not at rest while walls are to go, a lid works or grains are still to come.
      const bool walls_pending =
          state_.next_release < schedule_.releases.size() || control_.lid.enabled() || !pour_.done();
      const bool evaluate = schedule_.evaluation_due(s);
      const bool record = evaluate || (files_.wants_contacts() && schedule_.snapshot_due(s));
      if (record) sim_.request_contacts();
      try {
        allocating("a time step's contacts and forces", [&] { sim_.step(); });
      } catch (const CollectiveError& e) {
        stop_with_last_good_state(e);
      }
      if (evaluate) allocating("the grid stress and strain", [&] { grids_->evaluate(sim_); });
      const bool series_now = schedule_.series_due(s);
      if (series_now) {
        files_.record_series(sim_);
        // Every rank takes the same decision: the energies are the same bits everywhere.
        if (control_.rest_ratio > 0.0)
          r.stopped_at_rest = rest_held(s,
                                        s > state_.rest_check_from && !walls_pending &&
                                            sim_.kinetic_to_released() < control_.rest_ratio,
                                        rest_window_, state_);
      }
      if (files_.enabled() && (schedule_.snapshot_due(s) || r.stopped_at_rest)) {
        if (!series_now) files_.record_series(sim_);
        allocating("a snapshot (each rank's rows of the state; a force network's gathered on rank 0)",
                   [&] { files_.write_snapshot(sim_); });
        if (!r.stopped_at_rest) keep_replay_start();
      }
      clock_.dynamics(s, schedule_.total, control_.rest_ratio > 0.0, r.stopped_at_rest);
      if (r.stopped_at_rest) {
        // One more step, recorded, so that the final state has its stress and force network.
        if (((grids_ && !evaluate) || (files_.wants_contacts() && !record)) && !control_.relax_at_end)
          final_step();
        break;
      }
      const CheckpointClock::Decision d = checkpoints_.at(s, series_now, sim_.comm());
      fs::path written;
      if (d.write)
        written = allocating("a checkpoint (the engine's state, gathered on rank 0)",
                             [&] { return write_checkpoint_now(); });
      // At the last step the run goes on: what is left is its end (the writing, and a relaxation
      // that checks again), after which the driver exits with the signal's status.
      if (d.stop != 0 && s < schedule_.total) throw RunStopped(d.stop, s, written);
    }
    if (control_.relax_at_end) {
      if (const long lid = Lid::index(sim_); lid >= 0)
        sim_.set_wall_velocity(static_cast<std::size_t>(lid), dem::Vec3::Zero());
      dem::RelaxationOptions relaxation = control_.relaxation;
      relaxation.on_step = [&](const dem::RelaxationResult& now) {
        clock_.relaxation(now.steps, relaxation.max_steps,
                          std::max(now.max_force_residual, now.max_torque_residual),
                          relaxation.force_tolerance, now.converged);
        if (now.steps % kStopCheckEvery == 0) stop_in_relaxation(now.steps);
      };
      r.relaxation =
          allocating("the relaxation (FIRE)", [&] { return dem::relax_to_equilibrium(sim_, relaxation); });
      // One recorded step of the relaxed state for its stress, snapshot and series row.
      final_step();
    }
    // A resumed run counts the steps and time of every segment (run_history.h): its steps from
    // the run's first, which for a run of the driver is step 0.
    r.segment_seconds = clock_.seconds();
    r.history = history_;
    measure_final_state(sim_, history_.wall_seconds + r.segment_seconds,
                        history_.resumed_at.empty() ? sim_.step_count() - first_step_ : sim_.step_count(), r);
    r.inserted = pour_.state().inserted;
    if (grids_) {
      r.final_stress = grids_->final_stress();
      r.final_grid = grids_->final_grid();
      r.final_strain = grids_->final_strain();
    }
    if (control_.keep_wall_contacts && sim_.contacts_recorded())
      r.side_wall_contacts = side_wall_contacts(sim_);
    if (control_.keep_final_state) r.final_state = sim_.capture_state();
    // After the figures of the final state: a later state for differences moves the engine on.
    r.coarse_graining = states_.at_end(sim_);
    files_.write_summary(sim_, r);
    return r;
  }

 private:
  // A recorded step of the final state (after the run stopped at rest between evaluations, or
  // after the relaxation): its stress, series row and snapshot.
  void final_step() {
    if (grids_ || files_.wants_contacts()) sim_.request_contacts();
    sim_.step();
    if (grids_) grids_->evaluate(sim_);
    files_.record_series(sim_);
    files_.write_snapshot(sim_);
  }

  // The scene's controls before a step: the walls released, the lid, the pour. The run's loop
  // and the replay to the last good state call the same. Collective.
  void controls_before_step(dem::Simulation& sim, ScheduleState& state, Lid& lid, dem::Pour& pour) {
    release_walls(sim, schedule_, state);
    lid.before_step(sim);
    pour.before_step(sim);
  }

  // The state of the last snapshot, kept (on rank 0) for a replay to the last good state when
  // a guard stops the run. Collective.
  void keep_replay_start() {
    if (!files_.enabled()) return;
    replay_start_ = sim_.capture_state();
    replay_schedule_ = state_;
    replay_pour_ = pour_.state();
    replay_start_step_ = sim_.step_count();
  }

  // A guard stopped the run (runaway overlap, a non-finite state, a lost particle: dem/engine/
  // guards.h) in the step after the evaluation of step k = step_count(), whose state the guard
  // found wrong. The engine is then half-way into step k + 1, so its state is no longer one of
  // the run's. The last good state is step k - 1: the run is replayed to it from the state kept
  // at the last snapshot (the same steps, wall releases, lid and pour; with the deterministic
  // summation the same bits as the run had, docs/restart.md), checked against the guards, and
  // written as the last snapshot. The error then says where it is. Collective.
  [[noreturn]] void stop_with_last_good_state(const CollectiveError& e) {
    const long good = sim_.step_count() - 1;
    if (!files_.enabled() || good < replay_start_step_) throw e;
    std::string where;
    if (good == replay_start_step_) {
      where = "; the last good state, step " + std::to_string(good) + ", is the last snapshot written";
    } else {
      dem::Simulation replay(sim_.scene(), replay_start_, sim_.comm(), sim_.options());
      ScheduleState state = replay_schedule_;
      Lid lid(control_.lid);
      dem::Pour pour(replay.scene(), replay_pour_);
      try {
        while (replay.step_count() < good) {
          ++state.step;
          controls_before_step(replay, state, lid, pour);
          if (replay.step_count() + 1 == good && files_.wants_contacts()) replay.request_contacts();
          replay.step();
        }
      } catch (const CollectiveError&) {
        throw CollectiveError(
            std::string(e.what()) +
            "; the replay from the last snapshot to the step before failed as well: the last "
            "good state written is the last snapshot, step " +
            std::to_string(replay_start_step_));
      }
      // The replayed evaluation is checked as the next step would check it.
      if (!(replay.diagnostics().max_overlap_ratio <= dem::kRunawayOverlapRatio))
        throw CollectiveError(std::string(e.what()) + "; the replayed step " + std::to_string(good) +
                              " is not good either: the last good state written is the last snapshot, step " +
                              std::to_string(replay_start_step_));
      files_.write_snapshot(replay);  // checks that the state is finite and whole
      where = "; the last good state, step " + std::to_string(good) + ", is written as the last snapshot";
    }
    throw CollectiveError(std::string(e.what()) + where + " (" + (output_->folder / "snapshots").string() +
                          ")");
  }

  // A resumed run's history (rank 0's, from its checkpoint), on every rank: the earlier
  // segments' time, and this resume. Collective.
  void resume_history(const RunHistory& h, long step) {
    history_ = h;
    history_.resumed_at.push_back(step);
    long count = static_cast<long>(history_.resumed_at.size());
    MPI_Bcast(&count, 1, MPI_LONG, 0, sim_.comm());
    history_.resumed_at.resize(static_cast<std::size_t>(count));
    MPI_Bcast(history_.resumed_at.data(), static_cast<int>(count), MPI_LONG, 0, sim_.comm());
    MPI_Bcast(&history_.wall_seconds, 1, MPI_DOUBLE, 0, sim_.comm());
  }

  // A stop request during the relaxation at the end (minutes in the default study) ends it
  // (every rank at the same FIRE step: one reduction). The relaxation is not checkpointed:
  // a restart continues from the newest checkpoint and relaxes again, which with the
  // deterministic summation gives the same bytes (docs/restart.md). Collective.
  void stop_in_relaxation(long fire_steps) {
    const int signal = stop_signal_received(sim_.comm());
    if (signal == 0) return;
    fs::path newest;
    if (output_) {
      sim_.on_root([&] {
        const std::vector<fs::path> all = checkpoint_files(output_->folder);
        if (!all.empty()) newest = all.front();
      });
    }
    throw RunStopped(
        signal, state_.step, newest,
        output_ ? "no checkpoint yet: run the scene again (Output/overwrite = true, or another folder)" : "",
        "during the relaxation at the end (FIRE step " + std::to_string(fire_steps) +
            ", not checkpointed: a restart continues from the newest checkpoint and relaxes "
            "again)");
  }

  // Collective: the engine's state and the run's, written by rank 0.
  fs::path write_checkpoint_now() {
    Checkpoint c;
    c.engine = sim_.capture_state();
    fs::path written;
    sim_.on_root([&] {
      c.step = sim_.step_count();
      c.time = sim_.time();
      c.scene = output_->checkpoint.scene;
      c.run.schedule = state_;
      c.run.pour = pour_.state();
      c.run.files = files_.state();
      c.run.grids = grids_.has_value();
      if (grids_) c.run.grid_state = grids_->state();
      c.run.cg_reference = states_.reference();
      c.run.history = history_;
      c.run.history.wall_seconds += clock_.seconds();
      written = write_checkpoint(output_->folder, c, output_->checkpoint.keep);
    });
    checkpoints_.written();
    return written;
  }

  static inline const CheckpointOptions no_checkpoints_{};
  dem::Simulation& sim_;
  const RunControl& control_;
  const std::optional<OutputOptions>& output_;
  RunSchedule schedule_;
  RunFiles files_;
  std::optional<GridEvaluation> grids_;
  CheckpointClock checkpoints_;
  ProgressClock clock_;
  StateCapture states_;
  Lid lid_;
  dem::Pour pour_;    // insertion during the run (docs/insertion.md)
  long rest_window_;  // steps the bed stays below the rest ratio before the run stops
  ScheduleState state_;
  // The replay's start (keep_replay_start()): the state on rank 0, the schedule and the step.
  dem::EngineState replay_start_;
  ScheduleState replay_schedule_;
  dem::PourState replay_pour_;
  long replay_start_step_ = 0;
  long first_step_ = 0;  // the engine's step when this run began (a resumed run's checkpoint)
  RunHistory history_;   // the segments before this one (a fresh run: none)
  // FIRE steps between the relaxation's checks for a stop request (a reduction each).
  static constexpr long kStopCheckEvery = 1000;
};

}  // namespace

dem::ParticleStore fill_on_root(const dem::SceneConfig& scene, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  dem::ParticleStore fill;
  std::string error;
  if (rank == 0) {
    try {
      fill = allocating("the fill's grains", [&] { return dem::fill_container(scene); });
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  dem::throw_if_any(comm, error);
  return fill;
}

RunResult run_scene(const dem::SceneConfig& scene, const RunControl& control,
                    const std::optional<OutputOptions>& output, const ProgressReport& on_progress,
                    MPI_Comm comm, const dem::EngineOptions& options) {
  dem::Simulation sim(scene, fill_on_root(scene, comm), comm, options);
  return run_scene(sim, control, output, on_progress);
}

RunResult run_scene(dem::Simulation& sim, const RunControl& control,
                    const std::optional<OutputOptions>& output, const ProgressReport& on_progress) {
  SceneRun run(sim, control, output, on_progress, nullptr);
  return run.run();
}

RunResult resume_scene(const dem::SceneConfig& scene, const Checkpoint& checkpoint, const RunControl& control,
                       const OutputOptions& output, const ProgressReport& on_progress, MPI_Comm comm,
                       const dem::EngineOptions& options) {
  dem::Simulation sim(scene, checkpoint.engine, comm, options);
  const std::optional<OutputOptions> out = output;
  SceneRun run(sim, control, out, on_progress, &checkpoint.run);
  return run.run();
}

}  // namespace upgrain::coupling
