// Far from the origin: the same scene shifted by 1 km and by 100 km. A position there carries
// fewer digits below the grain scale: one unit in the last place (ulp) is 1.1e-13 m at 1 km
// and 1.5e-11 m at 100 km, so an overlap (a difference of positions) is known to about an ulp.
// A stack of spheres and a stack of ellipsoids, dropped and settled by the damped dynamics,
// must come to the same rest state as at the origin within what that rounding explains: the
// heights within 10 ulp per grain, and the floor force equal to the weight within what an
// ulp of overlap changes. Heights only: a stack on a point is neutral sideways (an offset e
// costs a force of m g e / 2r), so its horizontal rest position is not determined to the ulp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../common/scenes.h"
#include "dem/boundary/container.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/engine/simulation.h"
#include "dem/time_step.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

double ulp_at(double d) { return d == 0.0 ? 0.0 : std::nextafter(d, 2 * d) - d; }

struct AtRest {
  ParticleStore particles;  // positions relative to the shift
  double floor_force_error = 0.0;
  double kinetic = 0.0;  // J, at the end
};

// The scene's particles and its open box, all shifted by `d` along (1, 1, 1), after `settle_steps`.
AtRest settle_at(const SceneConfig& s, const ParticleStore& p0, double d, long settle_steps) {
  const Vec3 shift = Vec3::Constant(d);
  ParticleStore p = p0;
  for (std::size_t i = 0; i < p.size(); ++i) p.x[i] += shift;
  std::vector<PlaneWall> walls = make_open_box(s.container);
  for (PlaneWall& w : walls) w.point += shift;
  EngineOptions o;
  o.box = Box{shift, shift + Vec3(s.container.lx, s.container.ly, 0.05)};
  Simulation sim(s, p, walls, MPI_COMM_SELF, o);
  AtRest out;
  sim.run(settle_steps);
  out.kinetic = sim.energy().kinetic();
  out.particles = sim.gather_sorted_by_id();
  double weight = 0.0;
  for (std::size_t i = 0; i < out.particles.size(); ++i) {
    out.particles.x[i] -= shift;
    weight += out.particles.mass(i) * s.gravity;
  }
  out.floor_force_error = std::abs(-sim.wall_forces()[0].z() - weight) / weight;
  return out;
}

SceneConfig stack_scene() {
  SceneConfig s = test::bare_scene(1.0);
  s.particles.material = {2650.0, 5e9, 0.25};
  s.effects.gravity = true;
  s.effects.damping = true;
  s.damping_ratio = 0.5;
  s.container.lx = s.container.ly = 0.012;
  s.particles.radius = 1.5e-3;
  return s;
}

// Settles the stack at the origin and shifted by 1 km and 100 km for `steps` (the damped
// dynamics take its kinetic energy to round-off); `overlap` is the smallest overlap of the
// stack at rest (the top contact's).
void expect_same_rest(const SceneConfig& s, const ParticleStore& p, double overlap, long steps,
                      const char* what) {
  const AtRest origin = settle_at(s, p, 0.0, steps);
  for (double d : {1e3, 1e5}) {
    const double u = ulp_at(d);
    const AtRest far = settle_at(s, p, d, steps);
    double deviation = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
      deviation = std::max(deviation, std::abs(far.particles.x[i].z() - origin.particles.x[i].z()));
    // Expected: positions are multiples of an ulp, so each overlap (a difference of two) and
    // the force it gives are quantised; at rest the grains keep a jitter of a few ulp that
    // this quantisation drives (its kinetic energy scales as ulp^2: 1e-19 J at 1 km, 2e-15 J
    // at 100 km). Measured 9-15 ulp for these stacks; the bound is 10 ulp per grain of the
    // stack, the same number of ulps at both distances: rounding, nothing else.
    const double n = static_cast<double>(p.size());
    const double expected = 10.0 * n * u;
    // The force an ulp of overlap changes, relative: dF/F = 1.5 d(delta)/delta at the top.
    const double force_rounding = 1.5 * u / overlap;
    std::printf(
        "%s shifted by %.0f m: heights at rest differ by %.3e m = %.2f ulp, %.2f of the bound %.0f ulp; "
        "floor force - weight %.2e (origin %.2e; an ulp of the top overlap is %.2e of its force); "
        "kinetic energy %.1e J\n",
        what, d, deviation, deviation / u, deviation / expected, 10 * n, far.floor_force_error,
        origin.floor_force_error, force_rounding, far.kinetic);
    EXPECT_LT(deviation, expected) << what << " at " << d << " m";
    EXPECT_LT(far.floor_force_error, std::max(10 * force_rounding, 1e-9)) << what << " at " << d << " m";
  }
}

}  // namespace

TEST(HardFarFromOrigin, SphereStackShiftedBy1And100KmRestsWhereItDoesAtTheOrigin) {
  SceneConfig s = stack_scene();
  const double r = s.particles.radius;
  s.time_step = 0.9 * estimate_time_step(s).safe_step;
  ParticleStore p;
  for (int k = 0; k < 4; ++k)  // slightly apart, dropped
    p.add_sphere(k, r, 2650, Vec3(0.006, 0.006, r + 1e-5 + (2 * r + 1e-5) * k), Vec3::Zero(), Vec3::Zero());
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  const double top = hertz::overlap_for_force(cm.e_star, r / 2, p.mass(0) * s.gravity);
  expect_same_rest(s, p, top, 20000, "4 spheres");
}

TEST(HardFarFromOrigin, EllipsoidStackShiftedBy1And100KmRestsWhereItDoesAtTheOrigin) {
  SceneConfig s = stack_scene();
  const double a = s.particles.radius, c = 0.6 * a;
  s.particles.shapes = {ellipsoid_grain(0.8, 0.6, 1.0)};
  s.time_step = 0.9 * estimate_time_step(s).safe_step;
  ParticleStore p;
  for (int k = 0; k < 3; ++k)  // flat, aligned, slightly apart
    p.add_ellipsoid(k, {Vec3(a, 0.8 * a, c), 2650, Eigen::Quaterniond::Identity()},
                    {Vec3(0.006, 0.006, c + 1e-5 + (2 * c + 1e-5) * k), Vec3::Zero(), Vec3::Zero()});
  // The top contact's overlap, of the order of two spheres of radius c under one grain's weight.
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  const double top = hertz::overlap_for_force(cm.e_star, c / 2, p.mass(0) * s.gravity);
  expect_same_rest(s, p, top, 20000, "3 ellipsoids");
}
