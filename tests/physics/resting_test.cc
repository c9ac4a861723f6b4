// A sphere resting on the floor under gravity: the static overlap equals the Hertz value
// for its weight, delta = (3 m g / (4 E* sqrt(r)))^(2/3).
#include <gtest/gtest.h>

#include "../common/scenes.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

TEST(RestingSphere, StaticOverlapIsHertzForItsWeight) {
  for (double r : {1.5e-3, 5e-3}) {
    SceneConfig s = test::bare_scene(2e-6);
    s.effects.gravity = true;
    s.effects.damping = true;
    s.damping_ratio = 0.7;
    s.container.lx = s.container.ly = 0.1;
    ParticleStore p;
    p.add_sphere(0, r, 2650, Vec3(0.05, 0.05, r + 1e-4), Vec3::Zero(), Vec3::Zero());
    const double weight = p.mass(0) * 9.81;
    Simulation sim(s, p);
    sim.run(100000);
    const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
    const double expected = hertz::overlap_for_force(cm.e_star, r, weight);
    const double overlap = r - sim.particles().x[0].z();
    EXPECT_NEAR(overlap, expected, 1e-6 * expected) << "radius " << r;
    EXPECT_NEAR(sim.wall_forces()[0].z(), -weight, 1e-6 * weight);
  }
}
