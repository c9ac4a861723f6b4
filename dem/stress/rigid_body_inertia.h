#pragma once
// The inertial term of a rigid grain in the dynamic stress formulas (Yan and Regueiro eqs. 5-7;
// derivation in docs/stress.md, "Dynamic terms").
//
// For a material point at y from the centroid of a rigid grain, the acceleration is
// a = a^p + w_dot x y + w x (w x y). The average stress of the grain's material (force
// index first, t_i = sigma_ij n_j) is
//   integral sigma_ij dV = sum_c f_i (x^c - x^p)_j + integral rho (g_i - a_i) y_j dV,
// and with integral rho y dV = 0 the body-force and a^p parts drop out, leaving
//   D_ij = integral rho a_i y_j dV = eps_ikl w_dot_k Theta_lj + w_i w_k Theta_kj - |w|^2 Theta_ij,
// i.e. D = [w_dot]_x Theta + w (Theta w)^T - |w|^2 Theta, with the second moment
// Theta = integral rho y (x) y dV = tr(J)/2 1 - J in the world frame. Its skew part is
// [J w_dot + w x J w]_x / 2 = [T]_x / 2 by Euler's equations, which is what makes the
// modified forms symmetric in any state.
#include "dem/core/types.h"

namespace upgrain::dem {

// Theta from the moment-of-inertia tensor J (both in the same frame).
inline Mat3 second_moment_from_inertia(const Mat3& inertia) {
  return 0.5 * inertia.trace() * Mat3::Identity() - inertia;
}

// Theta_world = Q Theta_body Q^T for a grain of orientation Q.
inline Mat3 second_moment_in_world(const Mat3& theta_body, const Eigen::Quaterniond& orientation) {
  const Mat3 q = orientation.toRotationMatrix();
  return q * theta_body * q.transpose();
}

// D = integral rho a_rel (x) y dV for the rigid-body acceleration field about the centroid.
inline Mat3 rigid_body_inertial_moment(const Mat3& theta, const Vec3& omega, const Vec3& omega_dot) {
  Mat3 spin_rate;  // [w_dot]_x, (i,l) = eps_ikl w_dot_k
  spin_rate << 0.0, -omega_dot.z(), omega_dot.y(), omega_dot.z(), 0.0, -omega_dot.x(), -omega_dot.y(),
      omega_dot.x(), 0.0;
  return spin_rate * theta + omega * (theta * omega).transpose() - omega.squaredNorm() * theta;
}

// Angular acceleration from Euler's equations in the world frame,
// J w_dot = T - w x (J w).
inline Vec3 angular_acceleration(const Mat3& inertia, const Vec3& omega, const Vec3& torque) {
  return inertia.ldlt().solve(torque - omega.cross(inertia * omega));
}

}  // namespace upgrain::dem
