// Head-on collision of two equal spheres without gravity or walls: the contact duration
// against the analytic Hertz value (Johnson 1985, eq. 11.24), restitution 1 without
// damping, and restitution strictly decreasing with the damping ratio.
#include <gtest/gtest.h>

#include <cmath>

#include "../common/scenes.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

struct Collision {
  double duration;
  double restitution;
};

Collision collide(double zeta, double v_rel, int steps_per_contact) {
  const double r = 5e-3;
  SceneConfig s = test::bare_scene(1.0);
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  ParticleStore p;
  p.add_sphere(0, r, 2650, Vec3(-r - 1e-5, 0, 0), Vec3(0.5 * v_rel, 0, 0), Vec3::Zero());
  p.add_sphere(1, r, 2650, Vec3(r + 1e-5, 0, 0), Vec3(-0.5 * v_rel, 0, 0), Vec3::Zero());
  const double m = p.mass(0);
  const double t_hertz = hertz::contact_duration(cm.e_star, 0.5 * r, 0.5 * m, v_rel);
  s.time_step = t_hertz / steps_per_contact;
  s.effects.damping = zeta > 0.0;
  s.damping_ratio = zeta;
  Simulation sim(s, p, std::vector<PlaneWall>{});
  long in_contact = 0;
  double first = -1.0, last = -1.0;
  // Run until the spheres have separated after touching.
  for (long k = 0; k < 20L * steps_per_contact; ++k) {
    sim.step();
    const auto& q = sim.particles();
    const double gap = (q.x[1] - q.x[0]).norm() - 2 * r;
    if (gap < 0.0) {
      if (first < 0) first = sim.time();
      last = sim.time();
      ++in_contact;
    } else if (first >= 0) {
      break;
    }
  }
  (void)last;
  const auto& q = sim.particles();
  const double v_after = (q.v[1] - q.v[0]).x();  // > 0 once they fly apart
  return {static_cast<double>(in_contact) * s.time_step, v_after / v_rel};
}

}  // namespace

TEST(HeadOnCollision, DurationMatchesHertzWithinOnePercent) {
  for (double v : {0.1, 1.0, 5.0}) {
    const double r = 5e-3;
    const Material mat{2650.0, 1e8, 0.25};
    const double m = 2650 * 4.0 / 3 * M_PI * r * r * r;
    const double expected = hertz::contact_duration(effective_youngs_modulus(mat, mat), 0.5 * r, 0.5 * m, v);
    const Collision c = collide(0.0, v, 1000);
    EXPECT_NEAR(c.duration, expected, 0.01 * expected) << "impact speed " << v;
  }
}

TEST(HeadOnCollision, UndampedRestitutionIsOne) {
  const Collision c = collide(0.0, 1.0, 2000);
  EXPECT_NEAR(c.restitution, 1.0, 1e-6);
}

TEST(HeadOnCollision, RestitutionDecreasesWithDamping) {
  double previous = 1.0 + 1e-9;
  for (double zeta : {0.05, 0.1, 0.2, 0.4, 0.6, 0.8}) {
    const Collision c = collide(zeta, 1.0, 2000);
    EXPECT_LT(c.restitution, previous) << "zeta " << zeta;
    EXPECT_GT(c.restitution, 0.0) << "zeta " << zeta;
    previous = c.restitution;
  }
}

TEST(HeadOnCollision, RestitutionIndependentOfImpactSpeed) {
  // With c_n = 2 zeta sqrt(m* k_n) and the tangent Hertz stiffness, the damping force
  // scales like the elastic one, so e does not depend on the impact speed (docs/contact-law.md).
  const double e1 = collide(0.3, 0.1, 2000).restitution;
  const double e2 = collide(0.3, 3.0, 2000).restitution;
  EXPECT_NEAR(e1, e2, 1e-3);
}
