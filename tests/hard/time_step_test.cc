// The time step near and past its limit (docs/time-step.md): 0.9 and 1.0 of the safe step
// reach rest with the balance in its usual band; 1.5 times it is refused without the override;
// with the override, a step too large for the contacts is caught by the runaway-overlap guard,
// which names the contact, the step and the cause.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "coupling/run/scene_run.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "dem/time_step.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// 150 spheres dropped into a narrow box: a smaller cousin of the regression deposition.
SceneConfig small_deposition() {
  SceneConfig s;
  s.particles.count = 150;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = 0.015;
  s.fill.bottom_gap = 0.005;
  s.fill.position_jitter = 0.5;
  s.friction = 0.5;
  s.damping_ratio = 0.7;
  s.end_time = 1.5;  // an upper bound: the run stops at rest
  return s;
}

}  // namespace

TEST(HardTimeStep, NinetyAndHundredPercentOfTheSafeStepReachRest) {
  for (double fraction : {0.9, 1.0}) {
    SceneConfig s = small_deposition();
    const double safe = estimate_time_step(s).safe_step;
    s.time_step = fraction * safe;
    coupling::RunControl control;
    control.rest_ratio = 1e-6;
    const coupling::RunResult r = coupling::run_scene(s, control, std::nullopt);
    std::printf(
        "%.1f x safe step (%.3g s): %ld steps, at rest %d, KE/released %.2e, balance %.2e, max overlap "
        "%.3g\n",
        fraction, s.time_step, r.steps, r.stopped_at_rest, r.kinetic_to_released, r.energy_balance_error,
        r.diagnostics.max_overlap_ratio);
    EXPECT_TRUE(r.stopped_at_rest) << fraction;
    EXPECT_EQ(r.bed.particles_outside, 0);
    EXPECT_LT(std::abs(r.energy_balance_error), 0.01) << fraction;  // the deposition test's band
    EXPECT_LT(r.diagnostics.max_overlap_ratio, 0.05) << fraction;
  }
}

TEST(HardTimeStep, PastTheLimitTheGuardStopsTheRunNamingTheContactAndTheStep) {
  // What the override lets through (the driver refuses these steps without it: hard.unsafe_time_step).
  // 1.5 x the safe step still runs this deposition stably (the estimate has a margin); from 5 x
  // on, contacts overshoot and the runaway-overlap guard stops the run with its diagnosis.
  for (double factor : {1.5, 5.0, 10.0, 20.0}) {
    SceneConfig s = small_deposition();
    const double safe = estimate_time_step(s).safe_step;
    s.time_step = factor * safe;
    s.end_time = 0.1;
    std::string m;
    coupling::RunResult r;
    try {
      r = coupling::run_scene(s, coupling::RunControl{}, std::nullopt);
    } catch (const Error& e) {
      m = e.what();
    }
    std::printf("%.1f x: %s; balance %.3e, max overlap %.3g\n", factor, m.empty() ? "ran" : m.c_str(),
                r.energy_balance_error, r.diagnostics.max_overlap_ratio);
    if (factor < 2) {
      EXPECT_EQ(m, "") << factor;
      EXPECT_LT(std::abs(r.energy_balance_error), 0.01) << factor;
    } else {
      EXPECT_NE(m.find("runaway overlap at step "), std::string::npos) << factor << ": " << m;
      EXPECT_NE(m.find(" with particle "), std::string::npos) << factor << ": " << m;
      EXPECT_NE(m.find("is too large for the impacts of this scene"), std::string::npos)
          << factor << ": " << m;
    }
  }
}
