// The oedometric test (coupling/studies/calibration/oedometer_run.h, docs/calibration.md) on the case
// with a closed form: a simple-cubic lattice of frictionless Hertz spheres, 2 x 2 columns of 4,
// touching each other and the box's walls, without gravity. Under the servo lid each column
// shortens by 3 sphere-pair and 2 wall closures of the Hertz law (dem::hertz_column_strain);
// the side walls and the lateral contacts carry nothing (K0 = 0, nu = 0, E = M).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../common/scenes.h"
#include "coupling/studies/calibration/oedometer_run.h"
#include "dem/boundary/container.h"
#include "dem/core/material.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

constexpr double kRadius = 1e-3, kDensity = 2650.0;

// 2 x 2 columns of `layers` frictionless Hertz spheres of radius kRadius, touching each other,
// in a box of side 4 r - squeeze (squeezed symmetrically: the walls and the lateral contacts
// close by squeeze / 4 and squeeze / 2), the walls with Coulomb coefficient wall_friction;
// damping ratio 0.5, gravity as asked.
struct Lattice {
  SceneConfig scene;
  ParticleStore grains;
};
Lattice lattice(int layers, bool gravity, double squeeze = 0.0, double wall_friction = 0.0) {
  constexpr double r = kRadius;
  Lattice l{test::bare_scene(2e-6), {}};
  SceneConfig& s = l.scene;
  s.effects.gravity = gravity;
  s.effects.damping = true;
  s.effects.wall_friction = wall_friction > 0.0;
  s.damping_ratio = 0.5;
  s.friction = 0.0;
  s.container.lx = s.container.ly = 4.0 * r - squeeze;
  for (double& f : s.container.friction) f = wall_friction;
  const double pitch = 2.0 * r - 0.5 * squeeze, first = r - 0.25 * squeeze;
  long id = 0;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        l.grains.add_sphere(id++, r, kDensity, Vec3(first + pitch * i, first + pitch * j, r + 2 * r * k),
                            Vec3::Zero(), Vec3::Zero());
  return l;
}

}  // namespace

TEST(OedometerLattice, HertzLatticeFollowsItsClosedForm) {
  constexpr double r = kRadius;
  constexpr int layers = 4;
  const Lattice l = lattice(layers, false);
  const SceneConfig& s = l.scene;
  Simulation sim(s, l.grains, make_open_box(s.container));
  coupling::OedometerOptions o;
  o.loading = coupling::OedometerLoading::lid;
  o.lid_stresses = {2.0e4, 4.0e4, 8.0e4};
  o.hold_time = 0.02;
  o.seating_time = 0.0;  // a flat top: the lid seats without impacts
  o.max_speed = 0.01;
  const std::vector<coupling::OedometerRecord> rec = coupling::run_oedometer(sim, o);
  ASSERT_EQ(rec.size(), 4U);
  const double e_star = effective_youngs_modulus(s.particles.material, s.particles.material);
  EXPECT_EQ(rec[0].height, 2.0 * layers * r);
  EXPECT_EQ(rec[0].lid_stress, 0.0);
  std::vector<OedometerState> loaded;
  for (std::size_t k = 1; k < rec.size(); ++k) {
    const coupling::OedometerRecord& q = rec[k];
    const double exact = hertz_column_strain(q.lid_stress, e_star, r, layers);
    std::printf(
        "target %.0f Pa: lid %.2f Pa, Bagi sigma_v %.2f Pa, sigma_h %.3g Pa, strain %.6e (closed form "
        "%.6e)\n",
        q.target, q.lid_stress, q.state.vertical_stress, q.state.horizontal_stress, q.state.vertical_strain,
        exact);
    // The servo holds the target; the bed's mean stress is the lid's (no gravity, at rest);
    // the strain is the closed form's at that stress.
    EXPECT_NEAR(q.lid_stress, q.target, 1e-5 * q.target);
    EXPECT_NEAR(q.state.vertical_stress, q.lid_stress, 1e-5 * q.lid_stress);
    EXPECT_NEAR(q.state.vertical_strain, exact, 1e-5 * exact);
    EXPECT_LT(std::abs(q.state.horizontal_stress), 1e-9 * q.lid_stress);
    loaded.push_back(q.state);
  }
  // The secant moduli against the closed form's.
  const std::vector<OedometerStep> steps = oedometer_steps(loaded);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const double s0 = rec[k + 1].lid_stress, s1 = rec[k + 2].lid_stress;
    const double m =
        (s1 - s0) / (hertz_column_strain(s1, e_star, r, layers) - hertz_column_strain(s0, e_star, r, layers));
    std::printf("step %zu: M %.5e Pa (closed form %.5e Pa), K0 %.2e, E %.5e Pa\n", k, steps[k].modulus, m,
                steps[k].k0, steps[k].youngs);
    EXPECT_NEAR(steps[k].modulus, m, 1e-4 * m);
    EXPECT_NEAR(steps[k].poisson, 0.0, 1e-9);
  }
}

// The oedometric test by gravity on the same lattice, 2 x 2 columns of 6, settled under its
// weight: raising the weight f-fold, each column's contacts close as the Hertz law says for the
// weight above them (dem::hertz_column_centroid), the mean vertical stress is f W / (2 A) by
// equilibrium, the side walls carry nothing (K0 = 0), and the step moduli are those of the
// closed form's centres of mass.
TEST(OedometerLattice, GravityLoadedColumnsFollowTheirClosedForm) {
  constexpr double r = kRadius;
  constexpr int layers = 6;
  const Lattice l = lattice(layers, true);
  const SceneConfig& s = l.scene;
  const double m = l.grains.mass(0), weight = 4 * layers * m * s.gravity, area = 16.0 * r * r;
  Simulation sim(s, l.grains, make_open_box(s.container));
  for (int k = 0; k < 50000; ++k) sim.step();  // 0.1 s: the lattice settles under its weight
  coupling::OedometerOptions o;
  o.loading = coupling::OedometerLoading::gravity;
  o.gravity_factors = {2.0, 4.0};
  o.hold_time = 0.05;
  const std::vector<coupling::OedometerRecord> rec = coupling::run_oedometer(sim, o);
  ASSERT_EQ(rec.size(), 3U);
  EXPECT_EQ(sim.gravity(), Vec3(0.0, 0.0, -s.gravity));  // restored
  const double e_star = effective_youngs_modulus(s.particles.material, s.particles.material);
  std::vector<OedometerState> states;
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const coupling::OedometerRecord& q = rec[k];
    const double f = k == 0 ? 1.0 : o.gravity_factors[k - 1];
    const double exact = hertz_column_centroid(f * m * s.gravity, e_star, r, layers);
    const double settlement = layers * r - exact;
    std::printf(
        "g x %.0f: centre of mass %.9e m (closed form %.9e, settlement %.3e m), sigma_v %.2f Pa, K0 %.2e\n",
        f, q.centroid, exact, settlement, q.state.vertical_stress,
        q.state.horizontal_stress / q.state.vertical_stress);
    EXPECT_EQ(q.gravity_factor, f);
    EXPECT_TRUE(q.at_rest);
    EXPECT_NEAR(q.centroid, exact, 1e-4 * settlement);
    EXPECT_DOUBLE_EQ(q.height, 2.0 * q.centroid);
    EXPECT_NEAR(q.state.vertical_stress, f * weight / (2.0 * area), 1e-12 * weight / area);
    EXPECT_LT(std::abs(q.state.horizontal_stress), 1e-9 * q.state.vertical_stress);
    states.push_back(q.state);
  }
  const std::vector<OedometerStep> steps = oedometer_steps(states);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const auto zc = [&](std::size_t i) {
      return hertz_column_centroid((i == 0 ? 1.0 : o.gravity_factors[i - 1]) * m * s.gravity, e_star, r,
                                   layers);
    };
    const double de = centroid_vertical_strain(zc(0), zc(k + 1)) - centroid_vertical_strain(zc(0), zc(k));
    const double exact = (states[k + 1].vertical_stress - states[k].vertical_stress) / de;
    std::printf("step %zu: M %.5e Pa (closed form %.5e Pa)\n", k, steps[k].modulus, exact);
    EXPECT_NEAR(steps[k].modulus, exact, 1e-4 * exact);
  }
}

// The oedometric test by gravity with side walls that carry part of the weight: the same lattice
// squeezed 0.3 um into a box with wall friction 0.5, so that the walls' Coulomb springs hold the
// columns up as they settle. sigma_v takes the walls' share out by equilibrium (the integral of
// -sigma_zz over the bed is f W zc - sum z_c F_z of the side walls' contacts); checked against
// the contacts' own virial, Bagi's sigma_zz over the box to the top grain, rescaled to the volume
// A 2 zc (independent of the walls' term, to the discretisation of the grains' weight in it).
TEST(OedometerLattice, GravityLoadingTakesTheSideWallsShareOut) {
  constexpr double r = kRadius;
  constexpr int layers = 6;
  const Lattice l = lattice(layers, true, 3e-7, 0.5);  // the walls carry 20-28 %
  const SceneConfig& s = l.scene;
  const double weight = 4 * layers * l.grains.mass(0) * s.gravity, area = s.container.lx * s.container.ly;
  Simulation sim(s, l.grains, make_open_box(s.container));
  for (int k = 0; k < 50000; ++k) sim.step();
  coupling::OedometerOptions o;
  o.loading = coupling::OedometerLoading::gravity;
  o.gravity_factors = {2.0};
  o.hold_time = 0.05;
  const std::vector<coupling::OedometerRecord> rec = coupling::run_oedometer(sim, o);
  ASSERT_EQ(rec.size(), 2U);
  for (const coupling::OedometerRecord& q : rec) {
    const double top = q.centroid + layers * r;
    const double virial = -q.bagi(2, 2) * area * top / (area * 2.0 * q.centroid);
    const double floor_only = q.gravity_factor * weight / (2.0 * area);
    std::printf(
        "g x %.0f: side walls' share %.4f, sigma_v %.4f Pa (f W/(2A) %.4f Pa, Bagi's virial %.4f Pa)\n",
        q.gravity_factor, q.side_wall_share, q.state.vertical_stress, floor_only, virial);
    EXPECT_GT(q.side_wall_share, 0.05);
    EXPECT_LT(q.state.vertical_stress, (1.0 - 0.5 * q.side_wall_share) * floor_only);
    EXPECT_NEAR(q.state.vertical_stress, virial, 1e-3 * floor_only);
  }
}
