// Grid stress by the static formulas (dem/stress/): Yan and Regueiro's printed asymmetry indices
// reproduced from its printed tensors within their rounding; sigma = F/A for a loaded
// simple-cubic packing; the exact skew-torque identity and additivity of Bagi's stress in
// a dynamic state.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../common/scenes.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "dem/stress/asymmetry.h"
#include "dem/stress/grid_stress.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// The range of RAI over tensors that round to the printed three significant digits.
std::pair<double, double> rai_range(const Mat3& printed) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < 20000; ++k) {
    Mat3 m = printed;
    for (int e = 0; e < 9; ++e) {
      const double v = printed(e / 3, e % 3);
      const double unit = std::pow(10.0, std::floor(std::log10(std::abs(v))) - 2);  // last printed digit
      m(e / 3, e % 3) = v + u(rng) * unit;
    }
    const double r = 100.0 * relative_asymmetry_index(m);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  return {lo, hi};
}

Mat3 rows(std::initializer_list<double> v) {
  Mat3 m;
  auto it = v.begin();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = *it++;
  return m;
}

}  // namespace

TEST(RelativeAsymmetryIndex, ReproducesThePapersPrintedValues) {
  // Paper Tables 2 and 4: (tensor as printed, RAI printed in %, its last-digit half unit).
  const struct {
    const char* name;
    Mat3 s;
    double rai, half_unit;
  } cases[] = {
      {"Weber, 68 spheres",
       rows({-6.44E+01, -1.15E+01, -2.72E+00, -8.11E+00, -6.16E+01, -5.34E+00, -1.37E+00, -5.50E+00,
             -1.09E+02}),
       15.1, 0.05},
      {"Weber, 153 spheres",
       rows(
           {-8.12E+01, -2.31E-01, 2.55E+00, -1.35E-04, -7.86E+01, -8.39E+00, 2.54E+00, -8.09E+00, -9.68E+01}),
       2.2, 0.05},
      {"Weber, 1,536 spheres",
       rows(
           {-1.88E+02, -9.42E+00, 4.69E+00, -9.95E+00, -1.90E+02, -1.05E+00, 5.62E+00, -5.35E-01, -2.55E+02}),
       5.2, 0.05},
      {"Drescher, 1,536 spheres",
       rows({-2.09E+02, -9.84E+00, 5.25E+00, -9.84E+00, -2.11E+02, -4.74E-01, 2.19E+02, 2.14E+02, 1.88E+01}),
       94.7, 0.05},
      {"Weber, 3,456 spheres",
       rows(
           {-2.29E+02, 1.11E+01, -2.17E+00, 1.14E+01, -2.29E+02, -1.89E+00, -2.07E+00, -1.57E+00, -3.56E+02}),
       1.7, 0.05},
  };
  for (const auto& c : cases) {
    const auto [lo, hi] = rai_range(c.s);
    EXPECT_GE(c.rai + c.half_unit, lo)
        << c.name << ": RAI of the printed tensor " << 100 * relative_asymmetry_index(c.s);
    EXPECT_LE(c.rai - c.half_unit, hi)
        << c.name << ": RAI of the printed tensor " << 100 * relative_asymmetry_index(c.s);
  }
  EXPECT_NEAR(100 * relative_asymmetry_index(cases[0].s), 15.0, 0.1);
  EXPECT_NEAR(100 * relative_asymmetry_index(cases[3].s), 94.73, 0.01);
}

TEST(RelativeAsymmetryIndex, SymmetricAndSkewLimits) {
  Mat3 sym = rows({-3, 1, 2, 1, -4, 0.5, 2, 0.5, -5});
  EXPECT_EQ(relative_asymmetry_index(sym), 0.0);
  Mat3 s = sym;
  s(0, 1) += 0.2;  // skew part 0.1 in (0,1)/(1,0)
  EXPECT_GT(relative_asymmetry_index(s), 0.0);
}

TEST(GridStress, SimpleCubicColumnsBetweenPlatesGiveFOverA) {
  // n x n columns of m spheres squeezed between a floor and a fixed top plate, no
  // gravity; relaxed to equilibrium, every contact of a column carries the same force F
  // and Bagi's stress over the box between the plates is sigma_zz = -n^2 F / A exactly.
  const int n = 3, m = 4;
  const double r = 5e-3, pitch = 2.2 * r, h = m * 2 * r * 0.995;
  SceneConfig s = test::bare_scene(2e-6);
  s.effects.damping = true;
  s.effects.rotation = true;
  s.effects.friction = true;
  s.damping_ratio = 1.0;
  ParticleStore p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < m; ++k)
        p.add_sphere((i * n + j) * m + k, r, 2650,
                     Vec3((i + 0.5) * pitch, (j + 0.5) * pitch, (k + 0.5) * h / m), Vec3::Zero(),
                     Vec3::Zero());
  std::vector<PlaneWall> plates{{"floor", Vec3::Zero(), Vec3(0, 0, 1), 0.5},
                                {"top", Vec3(0, 0, h), Vec3(0, 0, -1), 0.5}};
  Simulation sim(s, p, plates);
  sim.run(40000);
  sim.request_contacts();
  sim.step();
  RegularGrid box;
  box.hi = Vec3(n * pitch, n * pitch, h);
  const GridStress g = grid_stress(sim.particles(), sim.contacts(), box, {sim.gravity(), true});
  const double area = n * pitch * n * pitch;
  const double floor_force = sim.wall_forces()[0].z();  // force of the grains on the floor (< 0)
  const Mat3& b = g[StressFormula::bagi][0];
  EXPECT_NEAR(b(2, 2), floor_force / area, 1e-7 * std::abs(floor_force / area));
  EXPECT_NEAR(sim.wall_forces()[1].z(), -floor_force, 1e-7 * std::abs(floor_force));
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      if (a != 2 || c != 2) {
        EXPECT_NEAR(b(a, c), 0.0, 1e-9 * std::abs(b(2, 2)));
      }
  EXPECT_EQ(g.particles[0], n * n * m);
  EXPECT_EQ(g.internal_contacts[0], n * n * (m - 1));
  EXPECT_EQ(g.external_contacts[0], 0);
  EXPECT_EQ(g.wall_contacts[0], 2 * n * n);
  // At rest the dynamic formulas reduce to Bagi's: the inertial terms vanish and De
  // Saxce's body term balances the contact forces.
  for (StressFormula f :
       {StressFormula::modified_nicot, StressFormula::modified_de_saxce, StressFormula::de_saxce}) {
    EXPECT_LE((g[f][0] - b).norm(), 1e-9 * b.norm()) << name_of(f) << "\n" << g[f][0];
  }
}

TEST(GridStress, BagiSkewEqualsContactTorqueAndIsAdditive) {
  // A bed in the middle of its deposition: grains colliding, spinning, sliding.
  SceneConfig s;
  s.particles.count = 400;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = 0.02;
  s.fill.bottom_gap = 0.002;
  s.fill.position_jitter = 0.5;
  s.fill.velocity_jitter = 0.2;
  s.time_step = 1e-5;
  Simulation sim(s, fill_container(s));
  sim.run(6000);
  sim.request_contacts();
  sim.step();
  const ParticleStore& p = sim.particles();
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.x[i].z() + 1e-3);
  RegularGrid fine;
  fine.lo = Vec3(0, 0, 0);
  fine.hi = Vec3(0.02, 0.02, top);
  fine.n[0] = 2;
  fine.n[1] = 2;
  fine.n[2] = 3;
  RegularGrid whole = fine;
  whole.n[0] = whole.n[1] = whole.n[2] = 1;
  const GridStress g = grid_stress(p, sim.contacts(), fine, {sim.gravity(), true});
  const GridStress all = grid_stress(p, sim.contacts(), whole, {sim.gravity(), true});
  ASSERT_GT(sim.contacts().size(), 300u);

  std::vector<Vec3> torque(fine.num_cells(), Vec3::Zero());
  for (std::size_t i = 0; i < p.size(); ++i) torque[fine.cell_of(p.x[i])] += p.torque[i];
  Mat3 sum = Mat3::Zero();
  long external = 0;
  for (int c = 0; c < fine.num_cells(); ++c) {
    const Mat3 skew =
        0.5 * (g[StressFormula::bagi][c] - g[StressFormula::bagi][c].transpose()) * g.cell_volume;
    // skew_ij = -eps_ijk T_k / 2, i.e. skew(0,1) = -T_z/2, skew(1,2) = -T_x/2, skew(2,0) = -T_y/2.
    const double scale = g[StressFormula::bagi][c].norm() * g.cell_volume + 1e-300;
    EXPECT_NEAR(skew(0, 1), -0.5 * torque[c].z(), 1e-12 * scale) << "cell " << c;
    EXPECT_NEAR(skew(1, 2), -0.5 * torque[c].x(), 1e-12 * scale) << "cell " << c;
    EXPECT_NEAR(skew(2, 0), -0.5 * torque[c].y(), 1e-12 * scale) << "cell " << c;
    sum += g[StressFormula::bagi][c] * g.cell_volume;
    external += g.external_contacts[c];
  }
  EXPECT_TRUE((sum - all[StressFormula::bagi][0] * all.cell_volume).norm() <= 1e-12 * sum.norm())
      << sum << "\n vs \n"
      << all[StressFormula::bagi][0] * all.cell_volume;
  EXPECT_GT(external, all.external_contacts[0]);  // contacts across cells count for both cells
  EXPECT_GT(relative_asymmetry_index(all[StressFormula::bagi][0]), 0.0);  // a dynamic state: not symmetric

  // The modified forms carry the grains' rotational inertia, whose skew part is the same
  // torque (Euler's equations): they are symmetric in any state. De Saxce's form (4),
  // built from absolute positions, the body force and the accelerations, equals (7).
  for (int c = 0; c < fine.num_cells(); ++c) {
    const Mat3& mn = g[StressFormula::modified_nicot][c];
    const Mat3& bagi = g[StressFormula::bagi][c];
    const double scale = bagi.norm();
    EXPECT_LE((mn - mn.transpose()).norm(), 1e-12 * scale) << "cell " << c;
    EXPECT_GT((bagi - bagi.transpose()).norm(), 1e-6 * scale) << "cell " << c;  // the test has teeth
    EXPECT_LE((g[StressFormula::de_saxce][c] - g[StressFormula::modified_de_saxce][c]).norm(), 1e-12 * scale)
        << "cell " << c;
    EXPECT_EQ(g[StressFormula::modified_de_saxce][c], mn);
    // Nicot (5) removes the same inertial terms from Weber's internal sum.
    EXPECT_LE(((g[StressFormula::nicot][c] - g[StressFormula::weber][c]) - (mn - bagi)).norm(),
              1e-12 * scale);
  }
}

TEST(GridStress, LoneSpinningSphereGivesTheRigidBodyHoopStress) {
  // No contacts: the only stress in the grain is what holds it together against the
  // centripetal acceleration, V sigma = -integral rho a (x) y dV = (m r^2 / 5)(|w|^2 1 - w w^T).
  SceneConfig s = test::bare_scene(1e-5);
  s.effects.rotation = true;
  s.effects.friction = true;
  ParticleStore p;
  const double r = 5e-3;
  const Vec3 w(30.0, -20.0, 100.0);
  p.add_sphere(0, r, 2650, Vec3(1.7, -0.4, 2.0), Vec3(0.1, 0, 0), w);
  Simulation sim(s, p, std::vector<PlaneWall>{});
  sim.request_contacts();
  sim.step();
  RegularGrid box;
  box.lo = Vec3(1.6, -0.5, 1.9);
  box.hi = Vec3(1.8, -0.3, 2.1);
  const GridStress g = grid_stress(sim.particles(), sim.contacts(), box, {sim.gravity(), true});
  const double theta = sim.particles().mass(0) * r * r / 5.0;
  const Mat3 expected = theta * (w.squaredNorm() * Mat3::Identity() - w * w.transpose()) / box.cell_volume();
  for (StressFormula f : {StressFormula::nicot, StressFormula::modified_nicot,
                          StressFormula::modified_de_saxce, StressFormula::de_saxce}) {
    EXPECT_LE((g[f][0] - expected).norm(), 1e-14 * expected.norm()) << name_of(f) << "\n" << g[f][0];
  }
  EXPECT_EQ(g[StressFormula::bagi][0], Mat3::Zero());
  EXPECT_GT(expected(0, 0), 0.0);  // tension across the spin axis
  EXPECT_NEAR(g.solid_fraction[0], 4.0 / 3.0 * M_PI * r * r * r / box.cell_volume(), 1e-15);
}

TEST(GridStress, LoneSpinningEllipsoidGivesTheRigidBodyResult) {
  // No contacts, no torque: V sigma = -integral rho a (x) y dV with a = w_dot x y + w x (w x y),
  // i.e. -([w_dot]x Theta + (w w^T - |w|^2 1) Theta), where Theta = Q (m/5) diag(a^2, b^2, c^2) Q^T
  // is the ellipsoid's second moment and w_dot = -J^-1 (w x J w) from Euler's equations, both
  // computed here in the body frame independently of the stress code.
  SceneConfig s = test::bare_scene(1e-7);
  s.effects.rotation = true;
  ParticleStore p;
  const Vec3 axes(3e-3, 2e-3, 1e-3);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()));
  const Vec3 w_body(30.0, -20.0, 100.0);  // not about a principal axis: w_dot != 0
  p.add_ellipsoid(0, {axes, 2650, q}, {Vec3(1.7, -0.4, 2.0), Vec3(0.1, 0, 0), q * w_body});
  Simulation sim(s, p, std::vector<PlaneWall>{});
  sim.request_contacts();
  sim.step();
  const ParticleStore& after = sim.particles();
  RegularGrid box;
  box.lo = Vec3(1.6, -0.5, 1.9);
  box.hi = Vec3(1.8, -0.3, 2.1);
  const GridStress g = grid_stress(after, sim.contacts(), box, {sim.gravity(), true});
  const double m = after.mass(0);
  const Mat3 rot = after.orientation[0].toRotationMatrix();
  const Vec3 wb = rot.transpose() * after.omega[0];
  const Vec3 j = m / 5.0 *
                 Vec3(axes.y() * axes.y() + axes.z() * axes.z(), axes.x() * axes.x() + axes.z() * axes.z(),
                      axes.x() * axes.x() + axes.y() * axes.y());
  const Vec3 wdot_body = -(wb.cross(j.cwiseProduct(wb))).cwiseQuotient(j);
  const Mat3 theta = rot * (m / 5.0 * axes.cwiseProduct(axes)).asDiagonal() * rot.transpose();
  const Vec3 w = after.omega[0], wdot = rot * wdot_body;
  Mat3 cross_wdot;
  cross_wdot << 0, -wdot.z(), wdot.y(), wdot.z(), 0, -wdot.x(), -wdot.y(), wdot.x(), 0;
  const Mat3 expected =
      -(cross_wdot * theta + (w * w.transpose() - w.squaredNorm() * Mat3::Identity()) * theta) /
      box.cell_volume();
  for (StressFormula f : {StressFormula::nicot, StressFormula::modified_nicot,
                          StressFormula::modified_de_saxce, StressFormula::de_saxce}) {
    EXPECT_LE((g[f][0] - expected).norm(), 1e-12 * expected.norm()) << name_of(f) << "\n" << g[f][0];
  }
  EXPECT_GT(wdot.norm(), 100.0);  // the gyroscopic term is exercised
  EXPECT_NEAR(g.solid_fraction[0], 4.0 / 3.0 * M_PI * axes.prod() / box.cell_volume(), 1e-15);
}
