// The periodic cell (dem/core/periodic_cell.h, docs/periodic.md): the minimum image, the wrap
// with its image counter, exact images on the cell's grid; and through the engine on one rank
// (its own neighbour across every periodic face), a pair across each of the 26 faces, edges and
// corners against the same pair inside the cell, and a grain crossing a face many times.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "dem/core/error.h"
#include "dem/core/periodic_cell.h"
#include "dem/engine/simulation.h"

using namespace upgrain::dem;

namespace {

PeriodicCell cube_cell(double l, std::array<bool, 3> periodic = {true, true, true}) {
  Box b;
  b.hi = Vec3(l, l, l);
  return make_periodic_cell(b, periodic);
}

}  // namespace

TEST(PeriodicCell, MinimumImageIsTheNearestImageAlongPeriodicAxesOnly) {
  const PeriodicCell c = cube_cell(0.04, {true, false, true});
  const Vec3 d = minimum_image(c, Vec3(0.035, 0.035, -0.031));
  EXPECT_NEAR(d.x(), -0.005, 1e-15);
  EXPECT_EQ(d.y(), 0.035);  // bounded axis: unchanged
  EXPECT_NEAR(d.z(), 0.009, 1e-15);
  for (int a = 0; a < 3; a += 2) EXPECT_LE(std::abs(minimum_image(c, Vec3(0.0199, 0.0, 0.0199))[a]), 0.02);
}

TEST(PeriodicCell, WrapKeepsTheUnwrappedPositionAndCountsCrossings) {
  const PeriodicCell c = cube_cell(0.06, {true, true, false});
  // The faces and positions are on the cell's grid: x - L, x + L and the unwrapped sum are exact.
  EXPECT_EQ(c.box.hi.x(), on_grid(0.06, c.quantum.x()));
  Vec3 x(on_grid(0.0612345, c.quantum.x()), on_grid(-0.13, c.quantum.y()), 0.5);
  const Vec3 before = x;
  ImageCount n{0, 0, 0};
  wrap(c, x, n);
  EXPECT_EQ(n[0], 1);
  EXPECT_EQ(n[1], -3);
  EXPECT_EQ(n[2], 0);
  EXPECT_GE(x.x(), 0.0);
  EXPECT_LT(x.x(), c.box.hi.x());
  EXPECT_GE(x.y(), 0.0);
  EXPECT_LT(x.y(), c.box.hi.y());
  EXPECT_EQ(x.z(), 0.5);
  const Vec3 u = unwrapped(c, x, n);
  EXPECT_EQ(u.x(), before.x());
  EXPECT_NEAR(u.y(), before.y(), 1e-16);  // three cells: 3 L is not one add
}

TEST(PeriodicCell, ImagesOnTheGridAreExact) {
  const PeriodicCell c = cube_cell(0.06);
  const double q = c.quantum.x(), l = c.length(0);
  for (double x : {1e-9, 3.3e-4, 0.0011, 0.02987654321, 0.059}) {
    const double g = on_grid(x, q);
    EXPECT_EQ((g + l) - l, g) << x;
    EXPECT_EQ((g - l) + l, g) << x;
    // A pair seen from either image: the same branch vector.
    const double h = on_grid(0.0599 - x / 7, q);
    EXPECT_EQ(h - (g + l), (h - l) - g) << x;
  }
}

namespace {

// Two frictional, rotating spheres of radius r pressed together and sliding, centred on `mid`,
// in a fully periodic cube of side l (no walls, no gravity), run `steps` steps on one rank.
struct PairRun {
  Vec3 force_a, force_b, torque_a, x_a, x_b, v_a, omega_a;
  double tangential_elastic = 0.0;
  long contacts = 0;
};

PairRun run_pair(const Vec3& mid, long steps) {
  const double l = 0.02, r = 1e-3;
  SceneConfig s;
  s.particles.material = {2500.0, 1e8, 0.3};
  s.container.lx = s.container.ly = s.container.height = l;
  s.container.periodic = {true, true, true};
  s.effects.gravity = false;
  s.effects.friction = true;
  s.effects.rotation = true;
  s.effects.energy_tracking = true;
  s.friction = 0.5;
  s.damping_ratio = 0.2;
  s.time_step = 2e-7;
  const Vec3 u = Vec3(1.0, 0.7, 0.4).normalized() * (0.995 * r);
  ParticleStore p;
  p.add_sphere(0, r, 2500.0, mid - u, Vec3(0.01, -0.02, 0.015), Vec3(3, -1, 2));
  p.add_sphere(1, r, 2500.0, mid + u, Vec3(-0.01, 0.02, -0.005), Vec3(-2, 1, 4));
  Simulation sim(s, p, std::vector<PlaneWall>{});
  sim.run(steps);
  const ParticleStore a = sim.gather_sorted_by_id();
  const PeriodicCell& cell = sim.decomposition().cell();
  PairRun out;
  out.force_a = a.force[0];
  out.force_b = a.force[1];
  out.torque_a = a.torque[0];
  out.x_a = unwrapped(cell, a.x[0], a.image[0]) - mid;
  out.x_b = unwrapped(cell, a.x[1], a.image[1]) - mid;
  out.v_a = a.v[0];
  out.omega_a = a.omega[0];
  out.tangential_elastic = sim.energy().elastic_tangential;
  out.contacts = sim.diagnostics().particle_contacts;
  return out;
}

void expect_near_vec(const Vec3& a, const Vec3& b, double tol, const std::string& what) {
  EXPECT_LE((a - b).norm(), tol * std::max(1.0, b.norm()))
      << what << ": " << a.transpose() << " vs " << b.transpose();
}

}  // namespace

TEST(PeriodicCell, PairAcrossEachFaceEdgeAndCornerActsAsInsideTheCell) {
  const long steps = 150;
  const double l = 0.02;
  const Vec3 centre = Vec3::Constant(0.5 * l);
  const PairRun inside = run_pair(centre, steps);
  ASSERT_EQ(inside.contacts, 1);
  ASSERT_GT(inside.tangential_elastic, 0.0);  // the tangential spring carries history
  int directions = 0;
  for (int ex = -1; ex <= 1; ++ex)
    for (int ey = -1; ey <= 1; ++ey)
      for (int ez = -1; ez <= 1; ++ez) {
        if (ex == 0 && ey == 0 && ez == 0) continue;
        ++directions;
        // The pair's midpoint on the face, edge or corner in direction e: one grain on each side.
        const Vec3 mid = centre + 0.5 * l * Vec3(ex, ey, ez);
        const PairRun across = run_pair(mid, steps);
        const std::string what =
            "direction (" + std::to_string(ex) + ", " + std::to_string(ey) + ", " + std::to_string(ez) + ")";
        EXPECT_EQ(across.contacts, 1) << what << ": one pair, found once";
        expect_near_vec(across.force_a, inside.force_a, 1e-9, what + " force on a");
        expect_near_vec(across.force_b, inside.force_b, 1e-9, what + " force on b");
        expect_near_vec(across.torque_a, inside.torque_a, 1e-9, what + " torque on a");
        expect_near_vec(across.x_a, inside.x_a, 1e-12, what + " unwrapped position of a");
        expect_near_vec(across.x_b, inside.x_b, 1e-12, what + " unwrapped position of b");
        expect_near_vec(across.v_a, inside.v_a, 1e-9, what + " velocity of a");
        expect_near_vec(across.omega_a, inside.omega_a, 1e-9, what + " spin of a");
        EXPECT_NEAR(across.tangential_elastic, inside.tangential_elastic, 1e-9 * inside.tangential_elastic)
            << what << ": the tangential spring (history)";
      }
  EXPECT_EQ(directions, 26);
}

TEST(PeriodicCell, GrainCrossingAFaceManyTimesKeepsAContinuousUnwrappedPath) {
  const double l = 0.01, r = 1e-3;
  SceneConfig s;
  s.container.lx = s.container.ly = s.container.height = l;
  s.container.periodic = {true, true, true};
  s.effects.gravity = false;
  s.time_step = 1e-5;
  ParticleStore p;
  const Vec3 v(3.0, -1.3, 0.7);  // m/s: 30 cells along x in 0.1 s
  p.add_sphere(0, r, 2500.0, Vec3(0.005, 0.005, 0.005), v, Vec3::Zero());
  Simulation sim(s, p, std::vector<PlaneWall>{});
  const PeriodicCell& cell = sim.decomposition().cell();
  Vec3 last = Vec3(0.005, 0.005, 0.005);
  const long steps = 10000;
  for (long k = 0; k < steps; ++k) {
    sim.step();
    const ParticleStore& q = sim.particles();
    const Vec3 u = unwrapped(cell, q.x[0], q.image[0]);
    // One step's move, never a cell's jump.
    ASSERT_LT((u - last - s.time_step * v).norm(), 1e-12) << "step " << k;
    last = u;
  }
  const ParticleStore& q = sim.particles();
  EXPECT_EQ(q.image[0][0], 30);   // 0.005 + 0.3 m: 30.5 cells
  EXPECT_EQ(q.image[0][1], -13);  // 0.005 - 0.13 m: -12.5 cells
  EXPECT_EQ(q.image[0][2], 7);    // 0.005 + 0.07 m: 7.5 cells
  EXPECT_NEAR(last.x(), 0.005 + steps * s.time_step * v.x(), 1e-10);
  EXPECT_NEAR(last.y(), 0.005 + steps * s.time_step * v.y(), 1e-10);
  EXPECT_NEAR(last.z(), 0.005 + steps * s.time_step * v.z(), 1e-10);
  // Inside the cell after the last wrap, give or take the drift since.
  EXPECT_GT(q.x[0].x(), -l);
  EXPECT_LT(q.x[0].x(), 2 * l);
}

TEST(PeriodicCell, AxisNotLongerThanTwiceTheRangeIsRefused) {
  SceneConfig s;
  s.container.lx = 0.0045;  // the range is 2.4 mm (diameter 2 mm and a 0.4 mm skin)
  s.container.ly = s.container.height = 0.05;
  s.container.periodic = {true, false, false};
  s.effects.gravity = false;
  ParticleStore p;
  p.add_sphere(0, 1e-3, 2500.0, Vec3(0.002, 0.02, 0.02), Vec3::Zero(), Vec3::Zero());
  try {
    Simulation sim(s, p, std::vector<PlaneWall>{});
    FAIL() << "a 4.5 mm periodic x with 2.4 mm of interaction range was accepted";
  } catch (const upgrain::Error& e) {
    EXPECT_NE(std::string(e.what()).find("periodic axis x"), std::string::npos) << e.what();
  }
}

namespace {

// A cube cell sheared along x with the gradient z (Lees-Edwards), its tilt offset + turns L.
PeriodicCell sheared_cube(double l, double offset, std::int64_t turns) {
  PeriodicCell c = cube_cell(l);
  c.shear = {0, 2, on_grid(offset, c.quantum.x()), turns};
  return c;
}

}  // namespace

// The minimum image of a sheared cell is the nearest point of the lattice of images h n: short
// separations moved by random lattice vectors (the tilt's turns included) come back exactly to
// themselves, to round-off.
TEST(PeriodicCell, ShearedMinimumImageIsTheNearestImageOfTheTiltedLattice) {
  const double l = 0.04;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double offset : {0.0, 0.013, -0.0199, 0.02}) {
    const PeriodicCell c = sheared_cube(l, offset, 3);
    Mat3 h = Vec3::Constant(l).asDiagonal();
    h(0, 2) = c.tilt();
    for (int trial = 0; trial < 500; ++trial) {
      const Vec3 d(0.2 * l * u(rng), 0.2 * l * u(rng), 0.2 * l * u(rng));
      const Vec3 n(std::round(2.0 * u(rng)), std::round(2.0 * u(rng)), std::round(2.0 * u(rng)));
      const Vec3 m = minimum_image(c, d + h * n);
      ASSERT_LT((m - d).cwiseAbs().maxCoeff(), 1e-15) << "offset " << offset << ", n " << n.transpose();
    }
  }
}

// A grain that crosses the gradient axis's faces many times, through the shear axis's faces too,
// with the tilt remapped between crossings: every wrap keeps its unwrapped position x + h n to
// round-off (the unwrapped sums reach far past the cell, beyond its grid's exact range), the
// position stays in the box, and a remap moves no unwrapped position.
TEST(PeriodicCell, ShearedWrapKeepsTheUnwrappedPositionThroughCrossingsAndRemaps) {
  const double l = 0.04;
  PeriodicCell c = sheared_cube(l, 0.011, 0);
  const double qx = c.quantum.x(), qz = c.quantum.z();
  Vec3 x(on_grid(0.01, qx), on_grid(0.02, c.quantum.y()), on_grid(0.03, qz));
  ImageCount n{0, 0, 0};
  long crossings = 0;
  for (int k = 0; k < 400; ++k) {
    // A step on the grid, then the wrap: the unwrapped position is the step's.
    x += Vec3(on_grid(0.0173, qx), 0.0, on_grid(k % 3 == 0 ? -0.009 : 0.0131, qz));
    const Vec3 path = unwrapped(c, x, n);
    // Each of the unwrapped sums rounds at most once, to half an ulp of the sum.
    const double tolerance = 4.0 * 0x1p-53 * path.cwiseAbs().maxCoeff();
    const ImageCount before = n;
    wrap(c, x, n);
    crossings += std::abs(n[2] - before[2]);
    ASSERT_LE((unwrapped(c, x, n) - path).cwiseAbs().maxCoeff(), tolerance) << "step " << k;
    ASSERT_GE(x.x(), c.box.lo.x());
    ASSERT_LT(x.x(), c.box.hi.x());
    ASSERT_GE(x.z(), c.box.lo.z());
    ASSERT_LT(x.z(), c.box.hi.z());
    // Every fifth step the tilt grows by a quarter length (the images move) and is remapped: the
    // lattice is the same, and so is every unwrapped position.
    if (k % 5 == 4) {
      c.shear.offset += on_grid(0.25 * l, qx);
      const Vec3 before_remap = unwrapped(c, x, n);
      c.shear = remapped(c.shear, l);
      ASSERT_LE(std::abs(c.shear.offset), 0.5 * l);
      ASSERT_LE((unwrapped(c, x, n) - before_remap).cwiseAbs().maxCoeff(),
                4.0 * 0x1p-53 * before_remap.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_GT(crossings, 50);
  EXPECT_GT(c.shear.turns, 10);
}
