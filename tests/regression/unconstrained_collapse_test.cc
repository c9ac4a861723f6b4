// Yan and Regueiro's unconstrained collapse (their section 1, docs/stress.md): a column of grains deposited
// in a narrow box; when all four side walls are removed the column spreads freely on the floor. Checks that
// the walls hold, that their removal leaves no contact with them, that the pile spreads and slumps on every
// side, and that nothing is lost, sinks or gains energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "coupling/run/scene_run.h"
#include "dem/boundary/wall_release.h"
#include "dem/scene/fill.h"
#include "dem/time_step.h"

using namespace upgrain::dem;
using upgrain::coupling::run_scene;
using upgrain::coupling::RunControl;
using upgrain::coupling::RunResult;

namespace {
SceneConfig unconstrained_scene() {
  SceneConfig s;
  s.particles.count = 300;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = 0.015;
  s.container.ly = 0.015;
  s.container.side_walls_open_time = 0.3;
  s.fill.bottom_gap = 0.002;
  s.friction = 0.5;
  s.damping_ratio = 0.7;
  s.time_step = 1e-5;
  s.end_time = 1.2;
  return s;
}

struct Shape {
  double mass = 0.0;
  double top = 0.0;           // highest grain surface (m)
  double lowest_gap = 1e9;    // smallest z - r: a grain sinking into the floor makes it negative
  double lo[2] = {1e9, 1e9};  // horizontal extent of the grain surfaces
  double hi[2] = {-1e9, -1e9};
  double radius_of_gyration = 0.0;  // rms horizontal distance from the centre of mass (m)
  bool finite = true;
};

Shape shape(const ParticleStore& p) {
  Shape s;
  double cx = 0.0, cy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double m = p.mass(i);
    s.mass += m;
    cx += m * p.x[i].x();
    cy += m * p.x[i].y();
    s.top = std::max(s.top, p.x[i].z() + p.radius[i]);
    s.lowest_gap = std::min(s.lowest_gap, p.x[i].z() - p.radius[i]);
    for (int d = 0; d < 2; ++d) {
      s.lo[d] = std::min(s.lo[d], p.x[i][d] - p.radius[i]);
      s.hi[d] = std::max(s.hi[d], p.x[i][d] + p.radius[i]);
    }
    s.finite = s.finite && p.x[i].allFinite() && p.v[i].allFinite();
  }
  cx /= s.mass;
  cy /= s.mass;
  for (std::size_t i = 0; i < p.size(); ++i)
    s.radius_of_gyration += p.mass(i) * (std::pow(p.x[i].x() - cx, 2) + std::pow(p.x[i].y() - cy, 2));
  s.radius_of_gyration = std::sqrt(s.radius_of_gyration / s.mass);
  return s;
}
}  // namespace

TEST(UnconstrainedCollapse, ReleaseScheduleRemovesAllFourSideWallsAndKeepsTheFloor) {
  const SceneConfig s = unconstrained_scene();
  const std::vector<WallRelease> r = wall_releases(s.container);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].time, s.container.side_walls_open_time);
  ASSERT_EQ(r[0].walls.size(), 4u);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  for (const std::string& name : r[0].walls) {
    EXPECT_NE(name, "floor");
    EXPECT_TRUE(std::any_of(walls.begin(), walls.end(), [&](const PlaneWall& w) { return w.name == name; }))
        << name << " is not a wall of the box";
  }
  // The plain box releases nothing; the gate and the side walls come in time order.
  EXPECT_TRUE(wall_releases(BoxContainer{}).empty());
  BoxContainer both;
  both.gate_x = 0.02;
  both.gate_open_time = 0.5;
  both.side_walls_open_time = 0.2;
  const std::vector<WallRelease> b = wall_releases(both);
  ASSERT_EQ(b.size(), 2u);
  EXPECT_LT(b[0].time, b[1].time);
  EXPECT_EQ(b[1].walls.front(), kGateWallName);
}

TEST(UnconstrainedCollapse, TheColumnSpreadsOnTheFloorWhenTheSideWallsGo) {
  const SceneConfig s = unconstrained_scene();
  ASSERT_LE(s.time_step, estimate_time_step(s).safe_step);
  Simulation sim(s, fill_container(s));
  const long open_step = std::lround(s.container.side_walls_open_time / s.time_step);
  sim.run(open_step);
  const Shape before = shape(sim.particles());
  // The walls held the column: every grain inside the box, up to its elastic overlap with a
  // wall (measured below 0.5 % of a radius).
  const double overlap = 0.02 * s.particles.radius;
  EXPECT_GE(before.lo[0], -overlap);
  EXPECT_LE(before.hi[0], s.container.lx + overlap);
  EXPECT_GE(before.lo[1], -overlap);
  EXPECT_LE(before.hi[1], s.container.ly + overlap);

  for (const WallRelease& r : wall_releases(s.container))
    for (const std::string& w : r.walls) sim.remove_wall(w);
  sim.run(std::lround(0.6 / s.time_step));
  const Shape after = shape(sim.particles());

  ASSERT_TRUE(after.finite);
  EXPECT_EQ(sim.particles().size(), static_cast<std::size_t>(s.particles.count));
  EXPECT_NEAR(after.mass, before.mass, 1e-12 * before.mass);
  // No removed wall keeps a contact: their forces are exactly zero, the floor carries the pile.
  // Once the pile has slumped (no vertical acceleration left) the floor carries its weight.
  for (std::size_t w = 0; w < sim.walls().size(); ++w) {
    if (sim.walls()[w].name == "floor") {
      EXPECT_NEAR(-sim.wall_forces()[w].z(), after.mass * s.gravity, 0.02 * after.mass * s.gravity);
    } else {
      EXPECT_EQ(sim.wall_forces()[w].norm(), 0.0) << sim.walls()[w].name;
    }
  }
  // It spread past every former wall, and slumped.
  EXPECT_LT(after.lo[0], -s.particles.radius);
  EXPECT_GT(after.hi[0], s.container.lx + s.particles.radius);
  EXPECT_LT(after.lo[1], -s.particles.radius);
  EXPECT_GT(after.hi[1], s.container.ly + s.particles.radius);
  EXPECT_GT(after.radius_of_gyration, 1.5 * before.radius_of_gyration);
  EXPECT_LT(after.top, 0.75 * before.top);
  // No grain sank into the floor (overlaps stay far below a radius).
  EXPECT_GT(after.lowest_gap, -0.05 * s.particles.radius);
  std::printf(
      "unconstrained collapse: top %.4f -> %.4f m, radius of gyration %.4f -> %.4f m, "
      "extent x [%.4f, %.4f] y [%.4f, %.4f] m, lowest z - r %.2e m\n",
      before.top, after.top, before.radius_of_gyration, after.radius_of_gyration, after.lo[0], after.hi[0],
      after.lo[1], after.hi[1], after.lowest_gap);
}

// Spheres without rolling resistance that leave the pile roll on across the unbounded
// floor, so the run need not come to rest by the kinetic-energy rule; it must not stop
// before the walls open, and the energy must balance.
TEST(UnconstrainedCollapse, RunDepositionOpensTheWallsAtTheirTimeAndBalancesEnergy) {
  const SceneConfig s = unconstrained_scene();
  RunControl control;
  // A loose ratio: the column reaches it long before the walls open, and again just after
  // (it has not started to move), so the run must wait past the release to apply it.
  control.rest_ratio = 0.05;
  const RunResult r = run_scene(s, control, std::nullopt);
  const double settle = 0.1 * (s.end_time - s.container.side_walls_open_time);
  EXPECT_GT(r.simulated_time, s.container.side_walls_open_time + settle);
  EXPECT_GT(r.bed.particles_outside, 0) << "grains spread past the former walls";
  EXPECT_LT(std::abs(r.energy_balance_error), 0.02);
  // The removed walls carry nothing (wall_forces: the force of the grains on each wall).
  double sides = 0.0;
  for (std::size_t w = 0; w < r.wall_forces.size(); ++w)
    if (r.wall_names[w] != "floor") sides += r.wall_forces[w].norm();
  EXPECT_EQ(sides, 0.0);
  std::printf("run_scene: %ld steps, %.3f s, balance %.2e, KE/released %.2e\n", r.steps, r.simulated_time,
              r.energy_balance_error, r.kinetic_to_released);
}

// The extent of ellipsoids along each axis: a grain reaches x_d +- h(e_d), its support value
// h(n) = |D R^T n| (D = diag(a, b, c)), not its bounding radius.
struct Extent {
  double lo[3] = {1e9, 1e9, 1e9};
  double hi[3] = {-1e9, -1e9, -1e9};
};
Extent ellipsoid_extent(const ParticleStore& p) {
  Extent e;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Mat3 r = p.orientation[i].toRotationMatrix();
    for (int d = 0; d < 3; ++d) {
      const double h = r.row(d).transpose().cwiseProduct(p.semi_axes[i]).norm();
      e.lo[d] = std::min(e.lo[d], p.x[i][d] - h);
      e.hi[d] = std::max(e.hi[d], p.x[i][d] + h);
    }
  }
  return e;
}

// The same collapse with their ellipsoids (four shapes, a = 1.0-2.5 mm): the walls hold
// the column, and once they go it spreads and slumps on every side; nothing sinks into the
// floor, the quaternions stay unit and no contact solve fails.
TEST(UnconstrainedCollapse, EllipsoidsSpreadToo) {
  SceneConfig s = unconstrained_scene();
  s.particles.count = 150;
  s.particles.gradation = {{1.0e-3, 0.0}, {2.5e-3, 1.0}};
  s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(0.8, 0.6, 1.0),
                        ellipsoid_grain(0.8, 0.4, 1.0), ellipsoid_grain(0.6, 0.4, 1.0)};
  s.container.lx = s.container.ly = 0.02;
  s.container.side_walls_open_time = 0.2;
  s.time_step = 0.9 * estimate_time_step(s).safe_step;
  Simulation sim(s, fill_container(s));
  ASSERT_TRUE(sim.particles().has_shapes());
  sim.run(std::lround(s.container.side_walls_open_time / s.time_step));
  const Shape before = shape(sim.particles());
  const Extent held = ellipsoid_extent(sim.particles());
  // The walls held the column: every grain inside the box up to its elastic overlap with a
  // wall (a small fraction of the smallest semi-axis, 0.4 mm).
  const double overlap = 0.02 * 0.4e-3;
  for (int d = 0; d < 2; ++d) {
    EXPECT_GE(held.lo[d], -overlap);
    EXPECT_LE(held.hi[d], (d == 0 ? s.container.lx : s.container.ly) + overlap);
  }
  for (const WallRelease& r : wall_releases(s.container))
    for (const std::string& w : r.walls) sim.remove_wall(w);
  sim.run(std::lround(0.4 / s.time_step));
  const Shape after = shape(sim.particles());
  const Extent spread = ellipsoid_extent(sim.particles());
  ASSERT_TRUE(after.finite);
  EXPECT_NEAR(after.mass, before.mass, 1e-12 * before.mass);
  // Past every former wall, and slumped.
  for (int d = 0; d < 2; ++d) {
    EXPECT_LT(spread.lo[d], 0.0);
    EXPECT_GT(spread.hi[d], d == 0 ? s.container.lx : s.container.ly);
  }
  EXPECT_GT(after.radius_of_gyration, 1.5 * before.radius_of_gyration);
  EXPECT_LT(spread.hi[2], 0.95 * held.hi[2]);
  // No grain sank into the floor: its lowest surface point (support height along -z) stays
  // within a small fraction of the smallest semi-axis of the floor.
  EXPECT_GT(spread.lo[2], -overlap);
  const ParticleStore& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p.orientation[i].norm(), 1.0, 1e-12);
  EXPECT_EQ(sim.contact_solver_stats().failures, 0);
  EXPECT_EQ(sim.contact_solver_stats().uncertified, 0);
  std::printf(
      "ellipsoid unconstrained collapse: top %.4f -> %.4f m, radius of gyration %.4f -> %.4f m, extent x "
      "[%.4f, %.4f] y [%.4f, %.4f] m, lowest surface %.2e m, %lld solver calls\n",
      held.hi[2], spread.hi[2], before.radius_of_gyration, after.radius_of_gyration, spread.lo[0],
      spread.hi[0], spread.lo[1], spread.hi[1], spread.lo[2],
      static_cast<long long>(sim.contact_solver_stats().calls));
}
