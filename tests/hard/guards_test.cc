// The engine's guards fire (dem/engine/guards.h): each is triggered on purpose and its
// diagnosis checked, with the margin that separates it from a sound state.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "../common/scenes.h"
#include "dem/boundary/container.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// Runs `steps` and returns the guard's message, or "" when none fired.
std::string message_of_run(Simulation& sim, long steps) {
  try {
    sim.run(steps);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& m, const std::string& part) { return m.find(part) != std::string::npos; }

// Two spheres of radius r, ids 3 and 5, without gravity or walls, whose centres are
// 2r (1 - ratio / 2) apart: their overlap is `ratio` of a radius.
Simulation placed_inside(double ratio) {
  SceneConfig s = test::bare_scene(1e-6);
  s.effects.gravity = false;
  const double r = 5e-3;
  ParticleStore p;
  p.add_sphere(3, r, 2650, Vec3(0.05, 0.05, 0.05), Vec3::Zero(), Vec3::Zero());
  p.add_sphere(5, r, 2650, Vec3(0.05 + (2.0 - ratio) * r, 0.05, 0.05), Vec3::Zero(), Vec3::Zero());
  return Simulation(s, p, std::vector<PlaneWall>{});
}

}  // namespace

TEST(HardGuards, RunawayOverlapNamesTheContactTheStepAndTheCause) {
  // Placed 0.26 of a radius inside each other: the guard's limit is 0.25.
  Simulation sim = placed_inside(0.26);
  const std::string m = message_of_run(sim, 1);
  EXPECT_TRUE(contains(m, "runaway overlap at step 0 ")) << m;
  EXPECT_TRUE(contains(m, "of particle 3 with particle 5") || contains(m, "of particle 5 with particle 3"))
      << m;
  EXPECT_TRUE(contains(m, "reached 0.26 of a radius (limit 0.25)")) << m;
  EXPECT_TRUE(contains(m, "or a particle was placed inside another")) << m;
}

TEST(HardGuards, OverlapJustBelowTheLimitRunsOn) {
  // The margin: 0.24 of a radius is let through and pushed apart (no damping: they separate).
  Simulation sim = placed_inside(0.24);
  EXPECT_EQ(message_of_run(sim, 2000), "");
  EXPECT_GT((sim.particles().x[0] - sim.particles().x[1]).norm(), 2 * 5e-3);
}

TEST(HardGuards, GrainLostThroughTheFloorIsNamedWithTheWall) {
  // 200 m/s at a step of 1e-4 s: 20 mm (4 radii) per step, from just above the floor to well
  // below it in one step. The floor's contact then has an overlap of several radii.
  SceneConfig s = test::bare_scene(1e-4);
  s.container.lx = s.container.ly = 0.1;
  const double r = 5e-3;
  ParticleStore p;
  p.add_sphere(42, r, 2650, Vec3(0.05, 0.05, r + 1e-3), Vec3(0, 0, -200.0), Vec3::Zero());
  Simulation sim(s, p);
  const std::string m = message_of_run(sim, 3);
  EXPECT_TRUE(contains(m, "runaway overlap at step 1 ")) << m;
  EXPECT_TRUE(contains(m, "of particle 42 with wall 'floor'")) << m;
  EXPECT_TRUE(contains(m, "particle 42 is passing through wall 'floor'")) << m;
  EXPECT_TRUE(contains(m, "time step 0.0001 s (safe ")) << m;
}

TEST(HardGuards, NonFinitePositionIsNamedAtTheNextStep) {
  SceneConfig s = test::bare_scene(1e-5);
  s.container.lx = s.container.ly = 0.1;
  ParticleStore p;
  for (int k = 0; k < 4; ++k)
    p.add_sphere(10 + k, 5e-3, 2650, Vec3(0.02 + 0.02 * k, 0.05, 0.01), Vec3::Zero(), Vec3::Zero());
  Simulation sim(s, p);
  sim.run(10);
  // A velocity turned NaN (as a division by a zero mass would): the next drift moves the
  // position to NaN, which counts as moved, so the rebuild's guard names it at once.
  ParticleStore& q = sim.particles();
  for (int i = 0; i < sim.owned(); ++i)
    if (q.id[i] == 12) q.v[i].x() = std::numeric_limits<double>::quiet_NaN();
  const std::string m = message_of_run(sim, 1);
  EXPECT_EQ(m, "particle 12 has a non-finite position, velocity or orientation at step 10 (t = 0.0001 s)");
}
