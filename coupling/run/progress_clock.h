#pragma once
// What a run reports while it goes: the phase it is in, how far it is, the step rate of the
// last seconds and the time left at that rate. The rate of the whole run so far would be
// wrong: a deposition's first steps are free fall, several times cheaper than the steps of
// the bed that follows, so an average over them promised a quarter of the time the default
// study took. A run that stops at rest, and a relaxation that stops at its tolerance, may end
// before the step count the time left is reckoned to; the report says so.
#include <chrono>
#include <deque>
#include <functional>
#include <utility>

namespace upgrain::coupling {

struct Progress {
  enum class Phase { dynamics, relaxation };
  Phase phase = Phase::dynamics;
  long step = 0;                  // dynamics: the run's step; relaxation: the FIRE step
  long total_steps = 0;           // dynamics: the end time's step; relaxation: the step limit
  double steps_per_second = 0.0;  // over the last `ProgressClock::window` seconds
  double eta_seconds = 0.0;       // to `total_steps` at that rate
  bool may_end_sooner = false;    // the run stops at rest / the relaxation at its tolerance
  double residual = 0.0;          // relaxation: largest out-of-balance force over weight
  double tolerance = 0.0;         // relaxation: the residual it stops at
};
using ProgressReport = std::function<void(const Progress&)>;

// Reports at most once a second, and at the last step of a phase.
class ProgressClock {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr double window = 10.0;  // s of wall clock the rate is measured over

  // `report` empty: reports nothing (the ranks other than 0). `first_step`: the step the run
  // starts from (a resumed run's checkpoint).
  ProgressClock(ProgressReport report, long first_step);

  // The run at step `s` of `total`; `last`: the run ends here (at rest, or the last step).
  void dynamics(long s, long total, bool may_end_sooner, bool last);
  // The relaxation after FIRE step `s` of at most `limit`, with its residual and target.
  void relaxation(long s, long limit, double residual, double tolerance, bool last);

  // Wall-clock seconds since the clock was made.
  [[nodiscard]] double seconds() const;

 private:
  void report(Progress p, bool last);

  ProgressReport report_;
  Progress::Phase phase_ = Progress::Phase::dynamics;
  Clock::time_point start_, last_report_;
  std::deque<std::pair<Clock::time_point, long>> samples_;  // (time, step) over the window
};

}  // namespace upgrain::coupling
