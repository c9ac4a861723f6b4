#include "coupling/run/progress_clock.h"

#include <algorithm>

namespace upgrain::coupling {

namespace {
double seconds_between(ProgressClock::Clock::time_point a, ProgressClock::Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}
}  // namespace

ProgressClock::ProgressClock(ProgressReport report, long first_step)
    : report_(std::move(report)), start_(Clock::now()), last_report_(start_) {
  samples_.emplace_back(start_, first_step);
}

void ProgressClock::dynamics(long s, long total, bool may_end_sooner, bool last) {
  Progress p;
  p.phase = Progress::Phase::dynamics;
  p.step = s;
  p.total_steps = total;
  p.may_end_sooner = may_end_sooner && !last;
  report(p, last || s == total);
}

void ProgressClock::relaxation(long s, long limit, double residual, double tolerance, bool last) {
  Progress p;
  p.phase = Progress::Phase::relaxation;
  p.step = s;
  p.total_steps = limit;
  p.may_end_sooner = !last;
  p.residual = residual;
  p.tolerance = tolerance;
  report(p, last || s == limit);
}

void ProgressClock::report(Progress p, bool last) {
  if (!report_) return;
  const auto now = Clock::now();
  if (p.phase != phase_) {
    // A new phase: its own rate, from its first step.
    phase_ = p.phase;
    samples_.clear();
    samples_.emplace_back(now, 0);
    last_report_ = now;
    return;
  }
  if (seconds_between(last_report_, now) < 1.0 && !last) return;
  samples_.emplace_back(now, p.step);
  while (samples_.size() > 2 && seconds_between(samples_[1].first, now) >= window) samples_.pop_front();
  const auto& [then, from] = samples_.front();
  p.steps_per_second = static_cast<double>(p.step - from) / std::max(seconds_between(then, now), 1e-9);
  p.eta_seconds = static_cast<double>(p.total_steps - p.step) / std::max(p.steps_per_second, 1e-300);
  report_(p);
  last_report_ = now;
}

double ProgressClock::seconds() const { return seconds_between(start_, Clock::now()); }

}  // namespace upgrain::coupling
