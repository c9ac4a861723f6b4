// One contact evaluation: normal force, damping that never attracts, Mindlin spring build
// up, Coulomb cap with the spring rescaled, transport of the spring into a new tangent plane.
#include "dem/contact/contact_response.h"

#include <gtest/gtest.h>

#include "dem/contact/hertz_mindlin.h"

using namespace upgrain::dem;

namespace {
constexpr HertzNormal::Constants kHertz{.e_star = 2e7, .g_star = 8e6};
ContactParameters params() {
  return {.r_star = 1e-3, .m_star = 1e-5, .friction = 0.5, .zeta = 0.3, .dt = 1e-6};
}
ContactKinematics kinematics(double delta, const Vec3& vi = Vec3::Zero()) {
  ContactKinematics k;
  k.normal = Vec3(0, 0, 1);
  k.overlap = delta;
  k.lever_i = 1e-3 * k.normal;
  k.lever_j = -1e-3 * k.normal;
  k.v_i = vi;
  k.v_j = Vec3::Zero();
  k.omega_i = k.omega_j = Vec3::Zero();
  return k;
}
}  // namespace

TEST(ContactResponse, ElasticNormalForceIsHertz) {
  TangentialSpring spring;
  ContactEnergy e;
  const auto p = params();
  const auto f = contact_response<false, false, false, true>(kHertz, p, kinematics(1e-5), spring, e);
  EXPECT_DOUBLE_EQ(f.normal, hertz::normal_force(kHertz.e_star, p.r_star, 1e-5));
  EXPECT_TRUE(f.on_i.isApprox(Vec3(0, 0, -f.normal)));  // pushes i away from j
  EXPECT_NEAR(e.elastic_normal, hertz::normal_energy(kHertz.e_star, p.r_star, 1e-5),
              1e-12 * e.elastic_normal);
}

TEST(ContactResponse, DampingNeverAttracts) {
  TangentialSpring spring;
  ContactEnergy e;
  auto p = params();
  p.zeta = 5.0;
  // i moves away from j fast: elastic minus damping would be negative.
  const auto f =
      contact_response<false, true, false, true>(kHertz, p, kinematics(1e-7, Vec3(0, 0, -10)), spring, e);
  EXPECT_EQ(f.normal, 0.0);
  EXPECT_GT(e.dissipated_damping, 0.0);
  // Approaching: damping adds to the elastic force.
  ContactEnergy e2;
  const auto g =
      contact_response<false, true, false, true>(kHertz, p, kinematics(1e-7, Vec3(0, 0, 0.1)), spring, e2);
  EXPECT_GT(g.normal, hertz::normal_force(kHertz.e_star, p.r_star, 1e-7));
}

TEST(ContactResponse, SpringBuildsThenSlidesAtCoulombLimit) {
  const auto p = params();
  const double delta = 1e-5;
  const double k_t = hertz::tangential_stiffness(kHertz.g_star, p.r_star, delta);
  const double fn = hertz::normal_force(kHertz.e_star, p.r_star, delta);
  const Vec3 v(1e-3, 0, 0);  // i slides along +x relative to j
  TangentialSpring spring;
  ContactEnergy e;
  contact_response<true, false, false, true>(kHertz, p, kinematics(delta, v), spring, e);
  EXPECT_NEAR(spring.force.x(), -k_t * v.x() * p.dt, 1e-15);  // opposes the sliding
  for (int s = 0; s < 100000; ++s)
    contact_response<true, false, false, true>(kHertz, p, kinematics(delta, v), spring, e);
  EXPECT_NEAR(spring.force.norm(), p.friction * fn, 1e-12 * fn);
  EXPECT_LT(spring.force.x(), 0.0);
  EXPECT_GT(e.dissipated_friction, 0.0);
}

TEST(ContactResponse, SpringIsCarriedIntoTheNewTangentPlane) {
  const auto p = params();
  TangentialSpring spring{Vec3(1e-3, 0, 2e-4), 0.0};  // has a component along the current normal (0,0,1)
  const double before = spring.force.norm();
  ContactEnergy e;
  contact_response<true, false, false, false>(kHertz, p, kinematics(1e-5), spring, e);
  EXPECT_NEAR(spring.force.z(), 0.0, 1e-18);
  EXPECT_NEAR(spring.force.norm(), before, 1e-15);
}

TEST(ContactResponse, RotationEntersTheSlidingVelocity) {
  // omega_i about y with arm along +z gives a contact-point velocity along +x.
  const auto p = params();
  auto k = kinematics(1e-5);
  k.omega_i = Vec3(0, 2.0, 0);
  TangentialSpring with_rot, without;
  ContactEnergy e;
  contact_response<true, false, true, false>(kHertz, p, k, with_rot, e);
  contact_response<true, false, false, false>(kHertz, p, k, without, e);
  EXPECT_LT(with_rot.force.x(), 0.0);
  EXPECT_EQ(without.force.norm(), 0.0);
}
