// The rule that ends a run at rest (coupling/run/run_schedule.h; docs/scenes.md, "Stopping at
// rest"): the kinetic energy below the ratio at every time-series row of a window, restarted by
// a row above it; the window in settling times sqrt(d/g).
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/run/run_schedule.h"

using namespace upgrain;
using namespace upgrain::coupling;

TEST(RestRule, ALullShorterThanTheWindowDoesNotStopTheRun) {
  ScheduleState s;
  const long window = 100;
  // Rows every 10 steps: below from step 10 to 60, above at 70, below again from 80.
  EXPECT_FALSE(rest_held(10, true, window, s));
  EXPECT_EQ(s.below_rest_since, 10);
  EXPECT_FALSE(rest_held(60, true, window, s));
  EXPECT_FALSE(rest_held(70, false, window, s));
  EXPECT_EQ(s.below_rest_since, -1);
  for (long step = 80; step < 180; step += 10) EXPECT_FALSE(rest_held(step, true, window, s)) << step;
  EXPECT_TRUE(rest_held(180, true, window, s));  // 100 steps below since step 80
}

TEST(RestRule, AWindowOfZeroIsTheFirstRowBelow) {
  ScheduleState s;
  EXPECT_FALSE(rest_held(10, false, 0, s));
  EXPECT_TRUE(rest_held(20, true, 0, s));
}

TEST(RestRule, TheWindowIsInSettlingTimesOfTheLargestGrain) {
  dem::SceneConfig scene;
  scene.time_step = 1e-6;
  scene.particles.radius = 1.5e-3;
  scene.particles.gradation = {{0.5e-3, 0.0}, {2e-3, 1.0}};
  // sqrt(d/g) with d = 4 mm: 20.19 ms; two of them are 40,388 steps of 1 us.
  EXPECT_EQ(rest_window_steps(scene, 2.0), static_cast<long>(std::ceil(2.0 * std::sqrt(4e-3 / 9.81) / 1e-6)));
  EXPECT_EQ(rest_window_steps(scene, 0.0), 0);
  scene.effects.gravity = false;
  EXPECT_EQ(rest_window_steps(scene, 2.0), 0);  // no settling without gravity
}
