// Rolling resistance (elastic-plastic spring-dashpot, dem/contact/rolling_resistance.h;
// docs/contact-law.md). A sphere rolling on a flat floor is slowed by the constant plastic
// torque mu_r R* F_n; on a slope it stays put below the rolling angle atan(mu_r) and rolls
// above it; the energy balance stays closed with the rolling channels; the 1:1:0.1 disc of
// docs/ellipsoids.md comes to rest on its face.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "../common/scenes.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/contact/rolling_resistance.h"
#include "dem/engine/simulation.h"
#include "dem/time_step.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

constexpr double kG = 9.81;
constexpr double kR = 5e-3;
constexpr double kMuR = 0.05;

// A sphere resting on a frictional floor under gravity tilted by theta along x, at its static
// normal overlap, with rolling resistance on.
std::unique_ptr<Simulation> sphere_on_floor(double theta, const Vec3& v0, double eta_r = 0.3) {
  SceneConfig s = test::bare_scene(5e-6);
  s.effects.gravity = true;
  s.effects.damping = true;
  s.effects.wall_friction = true;
  s.effects.rotation = true;
  s.effects.rolling_resistance = true;
  s.damping_ratio = 0.5;
  s.rolling_friction = kMuR;
  s.rolling_damping_ratio = eta_r;
  s.container.lx = s.container.ly = 10.0;
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  const double m = 2650 * 4.0 / 3 * std::numbers::pi * kR * kR * kR;
  const double delta = hertz::overlap_for_force(cm.e_star, kR, m * kG * std::cos(theta));
  ParticleStore p;
  // Rolling without slip about the contact: omega = n_floor x v / r = z x v / r.
  p.add_sphere(0, kR, 2650, Vec3(1.0, 5.0, kR - delta), v0, Vec3::UnitZ().cross(v0) / (kR - delta));
  std::vector<PlaneWall> floor{{"floor", Vec3::Zero(), Vec3(0, 0, 1), 0.5}};
  auto sim = std::make_unique<Simulation>(s, p, floor);
  sim->set_gravity(kG * Vec3(std::sin(theta), 0, -std::cos(theta)));
  return sim;
}

}  // namespace

// Rolling without slip, the plastic torque M = mu_r r m g opposes the rolling: with the
// contact friction keeping v = omega r, (I + m r^2) domega/dt = -M, so the sphere decelerates
// at a = mu_r g r^2 / (I/m + r^2) = (5/7) mu_r g, and stops after t = v0 / a over
// s = v0^2 / (2 a). Without rolling resistance it would roll on for ever.
TEST(RollingResistance, RollingSphereStopsAtTheAnalyticDistanceAndTime) {
  const double v0 = 0.1;
  const auto owner = sphere_on_floor(0.0, Vec3(v0, 0, 0));
  Simulation& sim = *owner;
  const double dt = sim.time_step();
  const double a = 5.0 / 7.0 * kMuR * kG;
  const double t_stop = v0 / a, s_stop = v0 * v0 / (2 * a);
  double t_measured = -1, s_measured = 0;
  for (long k = 1; k <= static_cast<long>(1.5 * t_stop / dt); ++k) {
    sim.step();
    s_measured = std::max(s_measured, sim.particles().x[0].x() - 1.0);
    if (t_measured < 0 && sim.particles().v[0].x() <= 0.0) t_measured = k * dt;
  }
  ASSERT_GT(t_measured, 0.0) << "still rolling at " << sim.particles().v[0].x() << " m/s";
  EXPECT_NEAR(t_measured, t_stop, 0.02 * t_stop);
  EXPECT_NEAR(s_measured, s_stop, 0.02 * s_stop);
  // At rest afterwards (the spring and its dashpot hold it), not creeping back.
  EXPECT_LT(std::abs(sim.particles().v[0].x()), 1e-4 * v0);
  std::printf("rolling sphere: t_stop %.5f s (analytic %.5f), s_stop %.6f m (analytic %.6f)\n", t_measured,
              t_stop, s_measured, s_stop);
}

// On a slope below the rolling angle (tan theta < mu_r) the sphere stays at rest: the rolling
// spring takes up the torque m g sin(theta) r elastically, it does not creep, and it gains no
// energy. Above it (tan theta = 2 mu_r) it rolls with a = (5/7) g (sin theta - mu_r cos theta).
TEST(RollingResistance, SphereOnASlopeHoldsBelowTheRollingAngleAndRollsAbove) {
  {
    const double theta = std::atan(0.5 * kMuR);
    const auto owner = sphere_on_floor(theta, Vec3::Zero());
    Simulation& sim = *owner;
    const long quarter = static_cast<long>(0.25 / sim.time_step());
    auto mechanical = [&]() {
      const EnergyBalance e = sim.energy();
      return e.kinetic() + e.potential + e.elastic_normal + e.elastic_tangential + e.elastic_rolling;
    };
    const double e0 = mechanical();
    double x_quarter = 0.0, largest = 0.0;
    for (long k = 1; k <= 4 * quarter; ++k) {
      sim.step();
      if (k == quarter) x_quarter = sim.particles().x[0].x();
      if (k % 1000 == 0) largest = std::max(largest, mechanical() - e0);
    }
    const ParticleStore& q = sim.particles();
    // Elastic take-up only: the rolling spring turned by M / k_r under M = m g sin(theta) r,
    // plus the Mindlin spring's m g sin(theta) / k_t; then no creep.
    const double m = q.mass(0), f_n = m * kG * std::cos(theta), f_t = m * kG * std::sin(theta);
    const double e_star = HertzNormal::constants(test::bare_scene(1.0).particles.material, {}).pair.e_star;
    const double g_star = HertzNormal::constants(test::bare_scene(1.0).particles.material, {}).pair.g_star;
    const double delta = hertz::overlap_for_force(e_star, kR, f_n);
    const double k_r = rolling_stiffness(hertz::normal_stiffness(e_star, kR, delta), kMuR, kR);
    const double elastic = kR * (f_t * kR) / k_r + f_t / hertz::tangential_stiffness(g_star, kR, delta);
    EXPECT_NEAR(q.x[0].x() - 1.0, elastic, 0.03 * elastic);
    EXPECT_LT(std::abs(q.x[0].x() - x_quarter), 1e-9) << "creep over 0.75 s";
    EXPECT_LT(q.v[0].norm(), 1e-7);
    EXPECT_LT(largest, 1e-12) << "mechanical energy rose";  // J; the sphere's m g r is 3e-5 J
    std::printf(
        "slope below rolling angle: displacement %.4e m (elastic take-up %.4e), drift after 0.25 s %.3e m, "
        "largest mechanical energy rise %.3e J\n",
        q.x[0].x() - 1.0, elastic, q.x[0].x() - x_quarter, largest);
  }
  {
    const double theta = std::atan(2.0 * kMuR);
    const auto owner = sphere_on_floor(theta, Vec3::Zero());
    Simulation& sim = *owner;
    const long tenth = static_cast<long>(0.1 / sim.time_step());
    sim.run(tenth);
    const double v1 = sim.particles().v[0].x();
    sim.run(2 * tenth);
    const double a = (sim.particles().v[0].x() - v1) / 0.2;
    const double expected = 5.0 / 7.0 * kG * (std::sin(theta) - kMuR * std::cos(theta));
    EXPECT_NEAR(a, expected, 0.01 * expected);
    std::printf("slope above rolling angle: a %.5f m/s^2 (analytic %.5f)\n", a, expected);
  }
}

// 27 spheres dropped into a box with friction, damping and rolling resistance: the energy
// balance stays closed with the rolling spring's energy and its plastic and viscous
// dissipation booked, and that dissipation is far larger than the balance error (without the
// rolling channels the balance would be off by it).
TEST(RollingResistance, EnergyBalanceStaysClosed) {
  SceneConfig s = test::bare_scene(1e-5);
  s.effects = {true, true, true, true, true, true, true};
  s.damping_ratio = 0.3;
  s.rolling_friction = 0.1;
  s.container.lx = s.container.ly = 0.04;
  s.container.height = 0.2;
  Simulation sim(s, test::box_of_27_spheres(kR));
  sim.run(static_cast<long>(0.6 / s.time_step));
  const EnergyBalance e0 = sim.initial_energy(), e = sim.energy();
  const double released = e0.potential - e.potential + e0.kinetic();
  const double error = sim.energy_balance_error();
  EXPECT_LT(std::abs(error), 1e-2);
  EXPECT_GT(e.dissipated_rolling, 0.05 * released);
  EXPECT_GT(e.dissipated_rolling, 10.0 * std::abs(error) * released);
  std::printf(
      "energy balance: error %.3e, rolling dissipation %.3e, elastic rolling %.3e, stiffness change "
      "%.3e (of released)\n",
      error, e.dissipated_rolling / released, e.elastic_rolling / released,
      e.rolling_stiffness_change / released);
}
