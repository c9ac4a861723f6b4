// A sphere on an incline (a flat floor under tilted gravity). Analytic regimes:
//  - without rotation the sphere is a block: it sticks while tan(theta) < mu, and slides
//    with a = g (sin(theta) - mu cos(theta)) otherwise;
//  - with rotation and mu >= 2/7 tan(theta) it rolls without slip, a = 5/7 g sin(theta);
//  - with rotation and mu < 2/7 tan(theta) it slides while spinning up,
//    a = g (sin(theta) - mu cos(theta)).
#include <gtest/gtest.h>

#include <cmath>

#include "../common/scenes.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

constexpr double kG = 9.81;
constexpr double kR = 5e-3;

struct Motion {
  double acceleration;  // down-slope, fitted between 0.1 s and 0.3 s
  double max_displacement;
  double slip_velocity;  // v - omega r at the end
};

Motion roll(double theta_deg, double mu, bool rotation) {
  SceneConfig s = test::bare_scene(5e-6);
  s.effects.gravity = true;
  s.effects.damping = true;
  s.effects.wall_friction = true;
  s.effects.rotation = rotation;
  s.damping_ratio = 0.5;
  s.container.lx = s.container.ly = 10.0;
  const double theta = theta_deg * M_PI / 180.0;
  ParticleStore p;
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  const double m = 2650 * 4.0 / 3 * M_PI * kR * kR * kR;
  // Start at the static normal overlap so that the normal spring is not excited.
  const double delta = hertz::overlap_for_force(cm.e_star, kR, m * kG * std::cos(theta));
  p.add_sphere(0, kR, 2650, Vec3(1.0, 5.0, kR - delta), Vec3::Zero(), Vec3::Zero());
  BoxContainer box;
  box.friction[0] = mu;
  std::vector<PlaneWall> floor{{"floor", Vec3::Zero(), Vec3(0, 0, 1), mu}};
  Simulation sim(s, p, floor);
  sim.set_gravity(kG * Vec3(std::sin(theta), 0, -std::cos(theta)));
  Motion out{};
  const long steps_per_tenth = static_cast<long>(0.1 / s.time_step);
  double v1 = 0;
  for (int tenth = 1; tenth <= 3; ++tenth) {
    for (long k = 0; k < steps_per_tenth; ++k) {
      sim.step();
      out.max_displacement = std::max(out.max_displacement, std::abs(sim.particles().x[0].x() - 1.0));
    }
    if (tenth == 1) v1 = sim.particles().v[0].x();
  }
  const auto& q = sim.particles();
  out.acceleration = (q.v[0].x() - v1) / 0.2;
  out.slip_velocity = q.v[0].x() - q.omega[0].y() * kR;
  return out;
}

}  // namespace

TEST(Incline, BlockSticksBelowFrictionAngle) {
  const Motion m = roll(20.0, 0.5, false);  // tan 20 deg = 0.36 < 0.5
  // The undamped tangential spring oscillates about its loaded length: bounded, tiny.
  EXPECT_LT(m.max_displacement, 1e-3 * kR);
  std::printf("stick: max displacement %.3e m, fitted acceleration %.3e m/s^2\n", m.max_displacement,
              m.acceleration);
}

TEST(Incline, BlockSlidesAboveFrictionAngle) {
  const double theta = 35.0 * M_PI / 180.0;
  const Motion m = roll(35.0, 0.5, false);  // tan 35 deg = 0.70 > 0.5
  const double expected = kG * (std::sin(theta) - 0.5 * std::cos(theta));
  EXPECT_NEAR(m.acceleration, expected, 0.01 * expected);
}

TEST(Incline, SphereRollsWithoutSlip) {
  const double theta = 20.0 * M_PI / 180.0;
  const Motion m = roll(20.0, 0.5, true);  // 2/7 tan 20 deg = 0.10 < 0.5
  const double expected = 5.0 / 7.0 * kG * std::sin(theta);
  EXPECT_NEAR(m.acceleration, expected, 0.01 * expected);
  EXPECT_LT(std::abs(m.slip_velocity), 1e-3 * 0.3 * expected);
}

TEST(Incline, SphereSlidesWhenFrictionCannotHold) {
  const double theta = 30.0 * M_PI / 180.0;
  const Motion m = roll(30.0, 0.05, true);  // 2/7 tan 30 deg = 0.165 > 0.05
  const double expected = kG * (std::sin(theta) - 0.05 * std::cos(theta));
  EXPECT_NEAR(m.acceleration, expected, 0.01 * expected);
  EXPECT_GT(m.slip_velocity, 0.1);
}
