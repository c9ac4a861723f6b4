// Yan and Regueiro's constrained collapse (their section 1, docs/stress.md): grains deposited behind a gate
// in a wider box; when the gate is removed the bed collapses into the rest of the box. Checks that the gate
// holds, then releases, and that nothing is lost or gains energy.
#include <gtest/gtest.h>

#include <algorithm>

#include "coupling/run/scene_run.h"
#include "dem/scene/fill.h"
#include "dem/time_step.h"

using namespace upgrain::dem;
using upgrain::coupling::run_scene;
using upgrain::coupling::RunControl;
using upgrain::coupling::RunResult;

namespace {
SceneConfig collapse_scene() {
  SceneConfig s;
  s.particles.count = 400;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = 0.06;
  s.container.ly = 0.015;
  s.container.gate_x = 0.02;
  s.container.gate_open_time = 0.25;
  s.fill.bottom_gap = 0.002;
  s.friction = 0.5;
  s.damping_ratio = 0.7;
  s.time_step = 1e-5;
  s.end_time = 1.5;
  return s;
}

double max_x(const Simulation& sim) {
  double m = 0.0;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) m = std::max(m, sim.particles().x[i].x());
  return m;
}
}  // namespace

TEST(ConstrainedCollapse, TheGateHoldsTheBedThenReleasesIt) {
  const SceneConfig s = collapse_scene();
  ASSERT_LE(s.time_step, estimate_time_step(s).safe_step);
  // Deposition behind the gate.
  Simulation sim(s, fill_container(s));
  ASSERT_EQ(sim.walls().back().name, kGateWallName);
  for (std::size_t i = 0; i < sim.particles().size(); ++i)
    ASSERT_LT(sim.particles().x[i].x(), s.container.gate_x);
  sim.run(static_cast<long>(s.container.gate_open_time / s.time_step));
  EXPECT_LT(max_x(sim), s.container.gate_x);
  EXPECT_GT(sim.wall_forces().back().x(), 0.0) << "the bed leans on the gate: the grains push it along +x";
  auto top = [&] {
    double t = 0.0;
    for (std::size_t i = 0; i < sim.particles().size(); ++i)
      t = std::max(t, sim.particles().x[i].z() + sim.particles().radius[i]);
    return t;
  };
  const double top_before = top();
  sim.remove_wall(kGateWallName);
  sim.run(50000);                                    // 0.5 s
  EXPECT_GT(max_x(sim), s.container.gate_x + 0.01);  // grains ran out past the gate
  EXPECT_LT(top(), top_before - 0.005);              // and the bed slumped
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    EXPECT_GT(sim.particles().x[i].x(), 0.0);
    EXPECT_LT(sim.particles().x[i].x(), s.container.lx);
  }
  std::printf("collapse: top %.4f -> %.4f m, front at x = %.4f m (gate at %.3f m)\n", top_before, top(),
              max_x(sim), s.container.gate_x);

  // Whole run through run_scene: the gate opens at its time.
  RunControl control;
  control.rest_ratio = 1e-5;
  const RunResult r = run_scene(s, control, std::nullopt);
  EXPECT_TRUE(r.stopped_at_rest);
  EXPECT_GT(r.simulated_time, s.container.gate_open_time);
  EXPECT_EQ(r.bed.particles_outside, 0);
  EXPECT_LT(std::abs(r.energy_balance_error), 0.02);
  std::printf("run_scene: %ld steps, %.3f s, balance %.2e, KE/released %.2e\n", r.steps, r.simulated_time,
              r.energy_balance_error, r.kinetic_to_released);
}

// The same scene with their ellipsoids (four shapes, a = 1.0-2.5 mm): the gate holds
// them, they run out when it opens, nothing leaves the box, no contact solve fails.
TEST(ConstrainedCollapse, EllipsoidsCollapseToo) {
  SceneConfig s = collapse_scene();
  s.particles.count = 150;
  s.particles.gradation = {{1.0e-3, 0.0}, {2.5e-3, 1.0}};
  s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(0.8, 0.6, 1.0),
                        ellipsoid_grain(0.8, 0.4, 1.0), ellipsoid_grain(0.6, 0.4, 1.0)};
  s.container.gate_open_time = 0.2;
  s.time_step = 0.9 * estimate_time_step(s).safe_step;
  Simulation sim(s, fill_container(s));
  ASSERT_TRUE(sim.particles().has_shapes());
  sim.run(static_cast<long>(s.container.gate_open_time / s.time_step));
  EXPECT_LT(max_x(sim), s.container.gate_x);
  sim.remove_wall(kGateWallName);
  sim.run(static_cast<long>(0.4 / s.time_step));
  EXPECT_GT(max_x(sim), s.container.gate_x + 0.005);  // grains ran out past the gate
  const ParticleStore& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_GT(p.x[i].x(), 0.0);
    EXPECT_LT(p.x[i].x(), s.container.lx);
    EXPECT_GT(p.x[i].z(), 0.0);
    EXPECT_NEAR(p.orientation[i].norm(), 1.0, 1e-12);
  }
  EXPECT_EQ(sim.contact_solver_stats().failures, 0);
  EXPECT_EQ(sim.contact_solver_stats().uncertified, 0);
  std::printf("ellipsoid collapse: front at x = %.4f m, balance %.2e, %lld solver calls\n", max_x(sim),
              sim.energy_balance_error(), static_cast<long long>(sim.contact_solver_stats().calls));
}
