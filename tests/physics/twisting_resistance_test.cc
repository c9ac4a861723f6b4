// Twisting resistance (Hertz–Mindlin torsion of the contact circle, dem/contact/rolling_resistance.h;
// docs/contact-law.md). A sphere resting on a floor and spun about the floor's normal: without
// twisting resistance no torque of the law acts and it spins on; with it, a fast spin slips over
// the whole circle and stops under the constant torque 3 pi/16 mu a F_n (Johnson 1985, 7.4), and
// a small spin is held by the no-slip spring 16/3 G_tw a^3 (Lubkin 1951), whose torsional
// oscillation has the period 2 pi sqrt(I / k_tw). The energy balance stays closed.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "../common/scenes.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/contact/rolling_resistance.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

constexpr double kG = 9.81;
constexpr double kR = 5e-3;
constexpr double kMu = 0.5;

struct SpinningSphere {
  std::unique_ptr<Simulation> sim;
  double mass = 0.0, inertia = 0.0, a = 0.0;  // a: the contact radius sqrt(R delta)
};

// A sphere at its static overlap on a floor of friction kMu, spinning at omega0 about z.
SpinningSphere spinning_sphere(double omega0, bool twisting, double eta = 0.0) {
  SceneConfig s = test::bare_scene(2e-6);
  s.effects.gravity = true;
  s.effects.damping = true;
  s.effects.wall_friction = true;
  s.effects.rotation = true;
  s.effects.rolling_resistance = true;
  s.effects.twisting_resistance = twisting;
  s.damping_ratio = 0.5;
  s.rolling_friction = 0.05;
  s.rolling_damping_ratio = eta;
  s.container.lx = s.container.ly = 10.0;
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  SpinningSphere out;
  out.mass = 2650 * 4.0 / 3 * std::numbers::pi * kR * kR * kR;
  out.inertia = 0.4 * out.mass * kR * kR;
  const double delta = hertz::overlap_for_force(cm.e_star, kR, out.mass * kG);
  out.a = std::sqrt(kR * delta);
  ParticleStore p;
  p.add_sphere(0, kR, 2650, Vec3(1.0, 1.0, kR - delta), Vec3::Zero(), Vec3(0, 0, omega0));
  std::vector<PlaneWall> floor{{"floor", Vec3::Zero(), Vec3(0, 0, 1), kMu}};
  out.sim = std::make_unique<Simulation>(s, p, floor);
  return out;
}

}  // namespace

// Full slip: I domega/dt = -3 pi/16 mu a m g, so the spin stops after t = omega0 I / M. The
// torque on the circle is the same at every step once slipping, so the time is that of the
// law to within the last step and the spring's take-up (M / k_tw of twist, a few microradians).
TEST(TwistingResistance, SpinningSphereStopsUnderTheFullSlipTorque) {
  const double omega0 = 20.0;
  SpinningSphere off = spinning_sphere(omega0, false);
  off.sim->run(20000);
  EXPECT_NEAR(off.sim->particles().omega[0].z(), omega0, 1e-9 * omega0) << "no torque resists the spin";

  SpinningSphere on = spinning_sphere(omega0, true);
  Simulation& sim = *on.sim;
  const double torque = 3.0 * std::numbers::pi / 16.0 * kMu * on.a * on.mass * kG;
  const double t_stop = omega0 * on.inertia / torque;
  double t_measured = -1.0, after = 0.0;
  for (long k = 1; k <= static_cast<long>(1.5 * t_stop / sim.time_step()); ++k) {
    sim.step();
    const double w = sim.particles().omega[0].z();
    if (t_measured < 0 && w <= 0.0) t_measured = k * sim.time_step();
    if (t_measured > 0) after = std::max(after, std::abs(w));
  }
  ASSERT_GT(t_measured, 0.0) << "still spinning at " << sim.particles().omega[0].z() << " rad/s";
  EXPECT_NEAR(t_measured, t_stop, 0.01 * t_stop);
  // Held afterwards by the stuck spring: undamped here, it oscillates with at most the energy
  // it holds at the slip limit, 1/2 I omega^2 <= 1/2 M^2 / k_tw; no spin-up.
  const Material m = test::bare_scene(1.0).particles.material;
  const double k_tw =
      16.0 / 3.0 * 0.5 * m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio)) * std::pow(on.a, 3);
  const double bound = torque / std::sqrt(k_tw * on.inertia);
  EXPECT_LE(after, 1.001 * bound);
  // With the dashpot (the rolling damping ratio 0.3), the oscillation dies out.
  SpinningSphere damped = spinning_sphere(omega0, true, 0.3);
  damped.sim->run(static_cast<long>(1.5 * t_stop / damped.sim->time_step()));
  EXPECT_LT(std::abs(damped.sim->particles().omega[0].z()), 1e-6 * omega0);
  std::printf(
      "spinning sphere: stops after %.5f s (full-slip torque: %.5f s); then |omega| <= %.4f rad/s undamped "
      "(bound %.4f), %.2e rad/s damped\n",
      t_measured, t_stop, after, bound, std::abs(damped.sim->particles().omega[0].z()));
}

// No slip: a spin too small to reach the slip limit oscillates in the torsion spring with
// omega_osc = sqrt(k_tw / I), k_tw = 16/3 G_tw a^3, G_tw = G/2 for one material; the period
// from the zero crossings of the spin is that of the closed form.
TEST(TwistingResistance, SmallSpinOscillatesWithTheLubkinStiffness) {
  SpinningSphere s0 = spinning_sphere(0.0, true);
  const Material m = test::bare_scene(1.0).particles.material;
  const double g_tw = 0.5 * m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
  const double k_tw = 16.0 / 3.0 * g_tw * s0.a * s0.a * s0.a;
  const double period = 2.0 * std::numbers::pi * std::sqrt(s0.inertia / k_tw);
  // The largest spin that stays stuck: k_tw theta_max = M_slip with theta_max = omega / omega_osc.
  const double slip = 3.0 * std::numbers::pi / 16.0 * kMu * s0.a * s0.mass * kG;
  const double omega_small = 0.2 * slip / std::sqrt(k_tw * s0.inertia);
  SpinningSphere on = spinning_sphere(omega_small, true);
  Simulation& sim = *on.sim;
  ASSERT_LT(period / sim.time_step(), 1e5);
  ASSERT_GT(period / sim.time_step(), 50.0) << "the step resolves the oscillation";
  std::vector<double> crossings;
  double last = sim.particles().omega[0].z();
  for (long k = 1; crossings.size() < 7 && k < static_cast<long>(10 * period / sim.time_step()); ++k) {
    sim.step();
    const double now = sim.particles().omega[0].z();
    if ((last > 0.0) != (now > 0.0)) crossings.push_back((k - now / (now - last)) * sim.time_step());
    last = now;
  }
  ASSERT_EQ(crossings.size(), 7u);
  const double measured = (crossings[6] - crossings[0]) / 3.0;
  EXPECT_NEAR(measured, period, 0.01 * period);
  std::printf("torsional oscillation: period %.4e s (Lubkin stiffness: %.4e s)\n", measured, period);
}

// 27 spheres dropped spinning into a box with friction, damping, rolling and twisting
// resistance: the balance stays closed with the twisting spring booked in the rolling channels,
// and the twisting does dissipate (more than without it). The third run has twisting alone (a
// rolling friction of 0): no rolling spring, and still a closed balance.
TEST(TwistingResistance, EnergyBalanceStaysClosed) {
  double dissipated[3] = {0, 0, 0};
  for (int twisting = 0; twisting < 3; ++twisting) {
    SceneConfig s = test::bare_scene(1e-5);
    s.effects = {true, true, true, true, true, true, true, twisting >= 1};
    s.damping_ratio = 0.3;
    s.rolling_friction = twisting == 2 ? 0.0 : 0.1;
    s.container.lx = s.container.ly = 0.04;
    s.container.height = 0.2;
    Simulation sim(s, test::box_of_27_spheres(kR, 30.0));
    sim.run(static_cast<long>(0.6 / s.time_step));
    const EnergyBalance e0 = sim.initial_energy(), e = sim.energy();
    const double released = e0.potential - e.potential + e0.kinetic();
    const double error = sim.energy_balance_error();
    EXPECT_LT(std::abs(error), 1e-2);  // false for a NaN balance too
    dissipated[twisting] = e.dissipated_rolling / released;
    std::printf("twisting %d: balance error %.3e, rolling and twisting dissipation %.3e of released\n",
                twisting, error, dissipated[twisting]);
  }
  EXPECT_GT(dissipated[1], dissipated[0]);
  EXPECT_GT(dissipated[2], 0.0);
}
