// High-speed impacts: a sphere and a 1:0.8:0.6 ellipsoid hit the floor at 50 and 100 m/s, and
// a sphere hits a settled bed at 100 m/s, each at the safe step the scene's rule gives for
// that impact speed (docs/time-step.md: the Hertz contact time shortens as v^(-1/5)). No grain
// tunnels through the wall or another grain (the runaway-overlap guard would stop the run;
// the largest overlap is reported), and an elastic impact gains no energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../common/scenes.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "dem/time_step.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

double kinetic_energy(const ParticleStore& p) {
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    e += 0.5 * p.mass(i) * p.v[i].squaredNorm() + p.rotational_energy(i);
  }
  return e;
}

struct Impact {
  double gain = 0.0;         // (KE after - KE before) / KE before
  double max_overlap = 0.0;  // of the smallest semi-axis
  double lowest_centre = 0.0;
  long steps = 0;
};

// Glass-like grains: at 100 m/s Hertz gives an impact overlap of 0.13 of a radius, below the
// runaway-overlap limit (0.25); grains of 5 GPa would sink 0.27 (HardImpact.TooSoft...).
constexpr double kStiff = 29e9;

// One grain thrown at the floor at `speed`, elastic (no damping, no friction, no gravity),
// at `fraction` of the safe step, until it has left the floor.
Impact floor_impact(bool ellipsoid, double speed, double fraction = 1.0) {
  const double a = 1.5e-3;
  SceneConfig s = test::bare_scene(1.0);
  s.particles.material = {2650.0, kStiff, 0.25};
  s.effects = {false, false, false, false, true, true};
  s.particles.radius = a;
  if (ellipsoid) s.particles.shapes = {ellipsoid_grain(0.8, 0.6, 1.0)};
  s.time_step_rule.impact_speed = speed;
  const TimeStepEstimate ts = estimate_time_step(s);
  // The refusal accounts for the impact speed: the safe step is within 0.1 of the Hertz
  // contact time at that speed.
  EXPECT_EQ(ts.impact_speed, speed);
  EXPECT_LE(ts.safe_step, 0.1 * ts.hertz_time * (1 + 1e-12));
  s.time_step = fraction * ts.safe_step;
  ParticleStore p;
  const Vec3 start(0, 0, a + 1e-4);
  if (ellipsoid)
    p.add_ellipsoid(0,
                    {Vec3(a, 0.8 * a, 0.6 * a), 2650,
                     Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3(1, 0.4, 0.2).normalized()))},
                    {start, Vec3(0, 0, -speed), Vec3::Zero()});
  else
    p.add_sphere(0, a, 2650, start, Vec3(0, 0, -speed), Vec3::Zero());
  const double e0 = kinetic_energy(p);
  Simulation sim(s, p, {{"floor", Vec3::Zero(), Vec3::UnitZ(), 0.0}});
  Impact out;
  out.lowest_centre = start.z();
  bool touched = false;
  for (long k = 0; k < 100000; ++k) {
    sim.step();
    const StepDiagnostics d = sim.diagnostics();
    out.max_overlap = std::max(out.max_overlap, d.max_overlap_ratio);
    out.lowest_centre = std::min(out.lowest_centre, sim.particles().x[0].z());
    touched = touched || d.wall_contacts > 0;
    out.steps = k + 1;
    if (touched && d.wall_contacts == 0) break;
  }
  EXPECT_TRUE(touched);
  EXPECT_GT(sim.particles().v[0].z(), 0.0) << "it came back";
  out.gain = (kinetic_energy(sim.particles()) - e0) / e0;
  std::printf(
      "%s at %.0f m/s: dt %.3g s (%.2f of the safe step, %s-limited), %ld steps, max overlap %.4f of c, "
      "lowest centre %.3e m, energy gain %.2e of KE\n",
      ellipsoid ? "ellipsoid 1:0.8:0.6" : "sphere", speed, s.time_step, fraction, ts.limiting.c_str(),
      out.steps, out.max_overlap, out.lowest_centre, out.gain);
  return out;
}

}  // namespace

TEST(HardImpact, SphereAndEllipsoidBounceOffTheFloorAt50And100MetresPerSecond) {
  double worst = 0.0, worst_fine = 0.0;
  for (bool ellipsoid : {false, true})
    for (double speed : {50.0, 100.0}) {
      const Impact r = floor_impact(ellipsoid, speed);
      EXPECT_GT(r.lowest_centre, 0.0) << "no tunnelling";
      EXPECT_LT(r.max_overlap, 0.25);
      const Impact fine = floor_impact(ellipsoid, speed, 0.5);
      worst = std::max(worst, std::abs(r.gain));
      worst_fine = std::max(worst_fine, std::abs(fine.gain));
    }
  // An elastic contact resolved in 15-50 steps changes the energy by the integrator's error,
  // of either sign (it depends on where the last step falls in the contact): at most 2e-3 of
  // the kinetic energy, and less than half of it at half the step, so it is discretisation and
  // not energy the contact makes.
  std::printf("largest energy change at contact: %.2e of KE at the safe step, %.2e at half of it\n", worst,
              worst_fine);
  EXPECT_LT(worst, 2e-3);
  EXPECT_LT(worst_fine, 0.5 * worst);
}

TEST(HardImpact, TooSoftForTheImpactSpeedIsDiagnosedAsSuch) {
  // Grains of 5 GPa at 100 m/s: the law itself gives an overlap of 0.27 of a radius, above the
  // guard's limit at any step; the diagnosis says so instead of blaming the step.
  const double a = 1.5e-3, speed = 100.0;
  SceneConfig s = test::bare_scene(1.0);
  s.particles.material = {2650.0, 5e9, 0.25};
  s.effects = {false, false, false, false, true, true};
  s.particles.radius = a;
  s.time_step_rule.impact_speed = speed;
  s.time_step = 0.1 * estimate_time_step(s).safe_step;
  ParticleStore p;
  p.add_sphere(3, a, 2650, Vec3(0, 0, a + 1e-4), Vec3(0, 0, -speed), Vec3::Zero());
  Simulation sim(s, p, {{"floor", Vec3::Zero(), Vec3::UnitZ(), 0.0}});
  try {
    sim.run(20000);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    std::printf("%s\n", m.c_str());
    EXPECT_NE(m.find("of particle 3 with wall 'floor'"), std::string::npos) << m;
    EXPECT_NE(m.find("too soft for the impacts of this scene"), std::string::npos) << m;
    EXPECT_NE(m.find("at the expected impact speed 100 m/s sinks 0.27"), std::string::npos) << m;
  }
}

TEST(HardImpact, SphereAt100MetresPerSecondIntoASettledBedStaysInTheBox) {
  // 60 spheres deposited and relaxed, then one more thrown straight down at the bed's middle.
  SceneConfig s;
  s.particles.count = 60;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, kStiff, 0.25};
  s.container.lx = s.container.ly = 0.012;
  s.fill.bottom_gap = 0.001;
  s.friction = 0.5;
  s.damping_ratio = 0.5;
  s.time_step_rule.impact_speed = 100.0;
  s.time_step = estimate_time_step(s).safe_step;
  Simulation bed(s, fill_container(s));
  while (bed.time() < 0.05 || bed.kinetic_to_released() > 1e-4) bed.run(2000);
  ParticleStore p = bed.gather_sorted_by_id();
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  p.add_sphere(1000, 1.5e-3, 2650, Vec3(0.006, 0.006, top + 2e-3), Vec3(0, 0, -100.0), Vec3::Zero());
  Simulation sim(s, p);
  double max_overlap = 0.0, lowest = top;
  const long steps = std::lround(2e-3 / s.time_step);  // 2 ms: the projectile is stopped by then
  for (long k = 0; k < steps; ++k) {
    sim.step();
    max_overlap = std::max(max_overlap, sim.diagnostics().max_overlap_ratio);
    const ParticleStore& q = sim.particles();
    for (int i = 0; i < sim.owned(); ++i)
      if (q.id[i] == 1000) lowest = std::min(lowest, q.x[i].z());
  }
  const ParticleStore end = sim.gather_sorted_by_id();
  long outside = 0;
  for (std::size_t i = 0; i < end.size(); ++i)
    if (end.x[i].z() < 0 || end.x[i].x() < 0 || end.x[i].x() > 0.012 || end.x[i].y() < 0 ||
        end.x[i].y() > 0.012)
      ++outside;
  std::printf(
      "projectile at 100 m/s into a bed of 60: dt %.3g s, %ld steps, max overlap %.4f of r, lowest centre "
      "%.3e m, grains outside %ld, balance %.2e\n",
      s.time_step, steps, max_overlap, lowest, outside, sim.energy_balance_error());
  EXPECT_EQ(outside, 0);
  EXPECT_GT(lowest, 0.0);
  EXPECT_LT(max_overlap, 0.25);
  EXPECT_LT(std::abs(sim.energy_balance_error()), 0.01);
}
