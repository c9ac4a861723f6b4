// Rigid-body rotation (dem/motion/rigid_rotation.h): a torque-free triaxial body conserves
// |L| and shows no energy drift over 10^6 steps at a step of 1e-3 of the rotation period;
// the intermediate-axis (tennis-racket) flips come at the period of the exact solution
// (Landau and Lifshitz, Mechanics, sec. 37); a constant torque adds angular momentum
// exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "dem/core/particle_store.h"
#include "dem/motion/grain_rotation.h"
#include "dem/motion/rigid_rotation.h"

using namespace upgrain::dem;

namespace {

// Mean of v over [begin, end).
double mean(const std::vector<double>& v, std::size_t begin, std::size_t end) {
  double s = 0.0;
  for (std::size_t k = begin; k < end; ++k) s += v[k];
  return s / static_cast<double>(end - begin);
}

}  // namespace

TEST(RigidRotation, TorqueFreeTriaxialBodyKeepsAngularMomentumAndEnergy) {
  // An ellipsoid-like body 1 : 2 : 3 spinning mostly about its major axis of inertia,
  // off-axis enough to nutate.
  const Vec3 inertia(1.0, 2.0, 3.0);
  RigidRotationState s;
  s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  s.angular_momentum_body = Vec3(0.3, 0.5, 6.0);
  const Vec3 l0 = s.orientation * s.angular_momentum_body;
  const double e0 = rotational_energy(s, inertia);
  const double period = 2.0 * std::numbers::pi / s.angular_momentum_body.cwiseQuotient(inertia).norm();
  const double h = 1e-3 * period;
  const long steps = 1000000, every = 100;
  std::vector<double> energy;
  energy.reserve(steps / every);
  double max_l_error = 0.0, max_e_error = 0.0, max_norm_error = 0.0;
  for (long k = 1; k <= steps; ++k) {
    free_rotation_step(s, inertia, h);
    if (k % every == 0) {
      const double e = rotational_energy(s, inertia);
      energy.push_back(e);
      max_e_error = std::max(max_e_error, std::abs(e - e0) / e0);
      max_l_error = std::max(max_l_error, (s.orientation * s.angular_momentum_body - l0).norm() / l0.norm());
      max_norm_error = std::max(max_norm_error, std::abs(s.orientation.norm() - 1.0));
    }
  }
  // Drift: the mean energy over the last tenth of the run against the first tenth (the
  // bounded O(h^2) oscillation of a symplectic scheme averages out; a drift would not).
  const std::size_t n = energy.size(), tenth = n / 10;
  const double drift = std::abs(mean(energy, n - tenth, n) - mean(energy, 0, tenth)) / e0;
  std::printf("max |L - L0| / |L0| %.2e, energy: max deviation %.2e, drift %.2e, |q| - 1: %.1e\n",
              max_l_error, max_e_error, drift, max_norm_error);
  EXPECT_LT(max_l_error, 1e-8);
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(max_e_error, 1e-7);  // the bounded oscillation (measured 1.2e-8)
  EXPECT_LT(max_norm_error, 1e-14);
}

TEST(RigidRotation, IntermediateAxisFlipsAtTheExactPeriod) {
  // Spin about the intermediate axis with a small perturbation: the body flips over
  // periodically. Exact solution (Landau and Lifshitz sec. 37, L^2 > 2 E I2): omega_2 is
  // proportional to sn(tau, k) with tau = t sqrt((I3 - I2)(L^2 - 2 E I1) / (I1 I2 I3)) and
  // k^2 = (I2 - I1)(2 E I3 - L^2) / ((I3 - I2)(L^2 - 2 E I1)); it changes sign every 2 K(k).
  const Vec3 inertia(1.0, 2.0, 3.0);
  RigidRotationState s;
  const Vec3 omega0(1e-3, 1.0, 2e-3);
  s.angular_momentum_body = inertia.cwiseProduct(omega0);
  const double e = rotational_energy(s, inertia);
  const double l2 = s.angular_momentum_body.squaredNorm();
  const double i1 = inertia[0], i2 = inertia[1], i3 = inertia[2];
  ASSERT_GT(l2, 2 * e * i2);
  const double lambda = std::sqrt((i3 - i2) * (l2 - 2 * e * i1) / (i1 * i2 * i3));
  const double k = std::sqrt((i2 - i1) * (2 * e * i3 - l2) / ((i3 - i2) * (l2 - 2 * e * i1)));
  const double half_period = 2.0 * std::comp_ellint_1(k) / lambda;

  const double h = half_period / 20000.0;
  std::vector<double> crossings;
  double previous = s.angular_momentum_body[1];
  double t = 0.0;
  while (crossings.size() < 7 && t < 10 * half_period) {
    free_rotation_step(s, inertia, h);
    t += h;
    const double now = s.angular_momentum_body[1];
    if ((now > 0) != (previous > 0))
      crossings.push_back(t - h * now / (now - previous));  // linear interpolation
    previous = now;
  }
  ASSERT_GE(crossings.size(), 5u);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  std::printf("flip interval: measured %.6f, exact %.6f (relative difference %.2e)\n", measured, half_period,
              measured / half_period - 1.0);
  EXPECT_NEAR(measured / half_period, 1.0, 1e-2);
}

TEST(RigidRotation, ConstantTorqueAddsAngularMomentumExactly) {
  // dL/dt = T in the world frame, whatever the body does in between.
  const Vec3 inertia(0.5, 1.0, 2.0);
  RigidRotationState s;
  s.angular_momentum_body = Vec3(0.2, -0.4, 1.0);
  const Vec3 l0 = s.orientation * s.angular_momentum_body;
  const Vec3 torque(0.3, -0.1, 0.2);
  const double h = 1e-3;
  for (int k = 0; k < 5000; ++k) rotation_step(s, inertia, torque, h);
  const Vec3 l = s.orientation * s.angular_momentum_body;
  EXPECT_LE((l - (l0 + 5000 * h * torque)).norm(), 1e-12 * l.norm());
}

// The grains of a store turn two at a time (dem/motion/grain_rotation.cc): each grain gets the
// same bits as when it turns alone, for slow grains (turns below 1e-4 rad: the short series), a
// faster one (the longer series, chosen per lane) and a very fast one (which sends its pair to
// the one-at-a-time path), in both halves of the step.
TEST(GrainRotation, TwoAtATimeIsBitwiseOneAtATime) {
  ParticleStore all;
  // rad/s: at dt = 1e-5 s half-turns of about 2e-5, 1e-3 and 1 rad per principal-axis turn
  const double spins[] = {3.0, 200.0, 11.0, 2e5, -150.0, 0.5};
  for (int k = 0; k < 6; ++k) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 + k, Vec3(1.0, 0.5 * k, -0.2).normalized()));
    all.add_ellipsoid(k + 1, {Vec3(1.0, 0.8 - 0.05 * k, 0.5) * 1e-3, 2650.0, q},
                      {Vec3(0.01 * k, 0, 0), Vec3::Zero(), Vec3(spins[k], 0.3 * spins[k], -0.5 * spins[k])});
    all.torque.back() = Vec3(1e-6 * (k + 1), -2e-6, 3e-6 * k);
  }
  const double dt = 1e-5, half = 0.5 * dt;
  for (int pairing : {0, 1, 2}) {  // pairs (1, 2) (3, 4) (5, 6); (1, 4) (2, 3) (5, 6); (1, 5) (6, 2) (3, 4)
    ParticleStore together = all;
    if (pairing == 1) together.permute({0, 3, 1, 2, 4, 5});
    if (pairing == 2) together.permute({0, 4, 5, 1, 2, 3});
    rotation_first_half(together, together.size(), half, dt);
    rotation_second_half(together, together.size(), half);
    for (std::size_t i = 0; i < together.size(); ++i) {
      ParticleStore alone;
      const std::size_t k = static_cast<std::size_t>(together.id[i] - 1);
      alone.add_ellipsoid(all.id[k], {all.semi_axes[k], 2650.0, all.orientation[k]},
                          {all.x[k], Vec3::Zero(), all.omega[k]});
      alone.torque[0] = all.torque[k];
      rotation_first_half(alone, 1, half, dt);
      rotation_second_half(alone, 1, half);
      EXPECT_EQ(together.orientation[i].coeffs(), alone.orientation[0].coeffs())
          << "grain " << together.id[i];
      EXPECT_EQ(together.omega[i], alone.omega[0]) << "grain " << together.id[i];
    }
  }
}
