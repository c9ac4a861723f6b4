// Each contact's stiffnesses as the engine gives them to the contact tangent
// (dem/engine/contact_stiffnesses.h): the scene's law at the pair's overlap, against the hand
// formulas of Hertz-Mindlin (k_n = 2 E* a, k_t = 8 G* a, a = sqrt(R* delta); Johnson 1985, Mindlin
// 1949) and the linear spring's constants.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dem/engine/contact_stiffnesses.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// Two spheres of radii 1 mm and 0.8 mm overlapping by `delta` along a slanted line, no gravity,
// no walls: their one contact after a step.
std::vector<ContactStiffness> pair_contact(const SceneConfig& s, double delta) {
  const double r1 = 1e-3, r2 = 0.8e-3;
  const Vec3 n = Vec3(1.0, 2.0, -0.5).normalized();
  const Vec3 x1(0.03, 0.03, 0.05);
  ParticleStore p;
  p.add_sphere(0, r1, s.particles.material.density, x1, Vec3::Zero(), Vec3::Zero());
  p.add_sphere(1, r2, s.particles.material.density, x1 + (r1 + r2 - delta) * n, Vec3::Zero(), Vec3::Zero());
  Simulation sim(s, p, std::vector<PlaneWall>{});
  sim.request_contacts();
  sim.step();
  return contact_stiffnesses(sim);
}

SceneConfig two_grains(const std::string& law) {
  SceneConfig s;
  s.effects.gravity = false;
  s.particles.material = {2650.0, 1e8, 0.3};
  s.contact_law = law;
  s.time_step = 1e-8;  // the grains barely move in the step
  return s;
}

}  // namespace

TEST(ContactStiffnesses, HertzMindlinAtTheOverlap) {
  const SceneConfig s = two_grains("hertz-mindlin");
  const std::vector<ContactStiffness> c = pair_contact(s, 1e-5);
  ASSERT_EQ(c.size(), 1u);
  const double delta = 1.8e-3 - c[0].branch.norm();
  EXPECT_NEAR(delta, 1e-5, 1e-9) << "the step moved the grains";
  const double e = s.particles.material.youngs_modulus, nu = s.particles.material.poisson_ratio;
  const double e_star = e / (2.0 * (1.0 - nu * nu));
  const double g_star = e / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu));
  const double a = std::sqrt(1e-3 * 0.8e-3 / 1.8e-3 * delta);
  EXPECT_NEAR(c[0].normal_stiffness, 2.0 * e_star * a, 1e-12 * e_star * a);
  EXPECT_NEAR(c[0].tangential_stiffness, 8.0 * g_star * a, 1e-12 * g_star * a);
  EXPECT_NEAR(c[0].normal.dot(Vec3(1.0, 2.0, -0.5).normalized()), 1.0, 1e-12);
}

TEST(ContactStiffnesses, HookeIsItsConstants) {
  SceneConfig s = two_grains("hooke");
  s.law_parameters = {{"normal stiffness", 2e4}};
  const std::vector<ContactStiffness> c = pair_contact(s, 1e-5);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].normal_stiffness, 2e4);
  EXPECT_DOUBLE_EQ(c[0].tangential_stiffness, 2.0 / 7.0 * 2e4) << "the law's default k_t";
}
