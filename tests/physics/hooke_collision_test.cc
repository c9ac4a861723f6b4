// The linear spring-dashpot law (dem/contact/law/hooke.h) in a head-on collision of two equal
// spheres without gravity or walls, against the closed form of the damped oscillator
// m* delta'' + c delta' + k delta = 0, delta(0) = 0, delta'(0) = v0 (Cundall and Strack 1979;
// Schwager and Poeschel 2007, Granular Matter 9:465 for the force-zero end):
//   delta(t) = v0/omega_d exp(-zeta omega_0 t) sin(omega_d t),
// undamped: duration pi / omega_0 and restitution 1; damped, the force k delta + c delta' first
// reaches zero at t_f with cot(omega_d t_f) = omega_0 (2 zeta^2 - 1) / (2 zeta omega_d), after
// which the clamped law pushes no more: the grains part at delta'(t_f), and the overlap closes
// at t_f + delta(t_f) / |delta'(t_f)|. Without the clamp, restitution would be
// exp(-zeta pi / sqrt(1 - zeta^2)), the textbook value the clamped law exceeds.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../common/scenes.h"
#include "dem/contact/contact_laws.h"
#include "dem/engine/simulation.h"
#include "dem/time_step.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

constexpr double kR = 5e-3;
constexpr double kKn = 2e4;  // N/m

struct Collision {
  double duration;     // time with overlap (s)
  double restitution;  // separation speed / approach speed
};

double sphere_mass() { return 2650.0 * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR; }

Collision collide(double zeta, double v0, int steps_per_contact) {
  SceneConfig s = test::bare_scene(1.0);
  s.contact_law = "hooke";
  s.law_parameters = {{"normal stiffness", kKn}};
  s.effects.damping = zeta > 0.0;
  s.damping_ratio = zeta;
  ParticleStore p;
  p.add_sphere(0, kR, 2650, Vec3(-kR - 1e-6, 0, 0), Vec3(0.5 * v0, 0, 0), Vec3::Zero());
  p.add_sphere(1, kR, 2650, Vec3(kR + 1e-6, 0, 0), Vec3(-0.5 * v0, 0, 0), Vec3::Zero());
  const double omega0 = std::sqrt(kKn / (0.5 * sphere_mass()));
  s.time_step = std::numbers::pi / omega0 / steps_per_contact;
  Simulation sim(s, p, std::vector<PlaneWall>{});
  long in_contact = 0;
  bool touched = false;
  for (long k = 0; k < 20L * steps_per_contact; ++k) {
    sim.step();
    const auto& q = sim.particles();
    if ((q.x[1] - q.x[0]).norm() < 2 * kR) {
      touched = true;
      ++in_contact;
    } else if (touched) {
      break;
    }
  }
  const auto& q = sim.particles();
  return {static_cast<double>(in_contact) * s.time_step, (q.v[1] - q.v[0]).x() / v0};
}

// The closed form with the no-attraction clamp.
Collision closed_form(double zeta, double v0) {
  const double omega0 = std::sqrt(kKn / (0.5 * sphere_mass()));
  const double omega_d = omega0 * std::sqrt(1.0 - zeta * zeta);
  // omega_d t_f in (pi/2, pi]: the force vanishes before the overlap does.
  const double phase = std::atan2(2.0 * zeta * omega_d, omega0 * (2.0 * zeta * zeta - 1.0));
  const double t_f = phase / omega_d;
  const double decay = std::exp(-zeta * omega0 * t_f);
  const double delta = v0 / omega_d * decay * std::sin(omega_d * t_f);
  const double rate =
      v0 / omega_d * decay * (omega_d * std::cos(omega_d * t_f) - zeta * omega0 * std::sin(omega_d * t_f));
  return {t_f + delta / -rate, -rate / v0};
}

}  // namespace

TEST(HookeCollision, UndampedLastsHalfAPeriodAndRestitutesFully) {
  const double omega0 = std::sqrt(kKn / (0.5 * sphere_mass()));
  for (double v : {0.01, 0.1, 1.0}) {
    const Collision c = collide(0.0, v, 2000);
    const double expected = std::numbers::pi / omega0;  // independent of the speed: a linear spring
    EXPECT_NEAR(c.duration, expected, 2e-3 * expected) << "impact speed " << v;
    EXPECT_NEAR(c.restitution, 1.0, 1e-6) << "impact speed " << v;
  }
}

TEST(HookeCollision, DampedMatchesTheClampedClosedForm) {
  for (double zeta : {0.05, 0.2, 0.5, 0.8}) {
    const Collision c = collide(zeta, 0.5, 4000);
    const Collision e = closed_form(zeta, 0.5);
    EXPECT_NEAR(c.restitution, e.restitution, 1e-3 * e.restitution) << "zeta " << zeta;
    EXPECT_NEAR(c.duration, e.duration, 2e-3 * e.duration) << "zeta " << zeta;
    // The clamp only ever keeps energy in: above the unclamped exp(-zeta pi / sqrt(1 - zeta^2)).
    EXPECT_GT(c.restitution, std::exp(-zeta * std::numbers::pi / std::sqrt(1.0 - zeta * zeta)))
        << "zeta " << zeta;
  }
}

TEST(HookeCollision, RestitutionDoesNotDependOnTheImpactSpeed) {
  // A linear law has no velocity scale (Hertz's restitution with this dashpot does, weakly).
  const double slow = collide(0.3, 0.01, 2000).restitution;
  const double fast = collide(0.3, 1.0, 2000).restitution;
  EXPECT_NEAR(slow, fast, 1e-4);  // the same to the step's discretisation
}

TEST(HookeLaw, ForceStiffnessAndEnergyAreThoseOfALinearSpring) {
  const ContactParameters p{.r_star = 1e-3, .m_star = 1e-5, .friction = 0.5, .zeta = 0.0, .dt = 1e-6};
  const NormalResponse r = HookeNormal::response({.k_n = kKn, .k_t = 3e3}, p, 2e-5);
  EXPECT_DOUBLE_EQ(r.force, kKn * 2e-5);
  EXPECT_DOUBLE_EQ(r.stiffness, kKn);
  EXPECT_DOUBLE_EQ(r.tangential_stiffness, 3e3);
  EXPECT_DOUBLE_EQ(HookeNormal::energy(r, 2e-5), 0.5 * kKn * 2e-5 * 2e-5);
}

TEST(HookeLaw, TangentialStiffnessDefaultsToTwoSeventhsOfTheNormal) {
  SceneConfig s;
  s.contact_law = "hooke";
  s.law_parameters = {{"normal stiffness", 7e4}};
  const auto hooke = [&] {
    return constants_of<Hooke>(find_contact_law("hooke").constants(s.particles.material, s.law_parameters));
  };
  EXPECT_DOUBLE_EQ(hooke().pair.k_n, 7e4);
  EXPECT_DOUBLE_EQ(hooke().pair.k_t, 2e4);
  EXPECT_DOUBLE_EQ(hooke().wall.k_n, 7e4);  // a wall alike
  s.law_parameters.push_back({"tangential stiffness", 5e3});
  EXPECT_DOUBLE_EQ(hooke().pair.k_t, 5e3);
}

TEST(HookeLaw, TimeStepRuleIsAFractionOfTheLightestPairsContactTime) {
  SceneConfig s;  // r = 1.5 mm, rho = 2650
  s.contact_law = "hooke";
  s.law_parameters = {{"normal stiffness", kKn}};
  const TimeStepEstimate e = estimate_time_step(s);
  const double m = 2650 * 4.0 / 3 * std::numbers::pi * std::pow(1.5e-3, 3);
  const double t_c = std::numbers::pi * std::sqrt(0.5 * m / kKn);
  EXPECT_NEAR(e.contact_time, t_c, 1e-12 * t_c);
  EXPECT_DOUBLE_EQ(e.safe_step, s.time_step_rule.hertz_fraction * e.contact_time);
  EXPECT_EQ(e.limiting, "Hooke");
  EXPECT_EQ(e.rayleigh_time, 0.0);  // k_n is not the grains' elasticity
}

TEST(ContactLawTable, UnknownLawIsRefusedByName) {
  try {
    (void)find_contact_law("jkr");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Contact/law = 'jkr'"), std::string::npos);
  }
  EXPECT_STREQ(contact_law_table()[0].name, "hertz-mindlin");
}
