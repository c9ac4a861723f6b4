#pragma once
// Rotation of a rigid body with a full inertia tensor: the symplectic splitting of
// Dullweber, Leimkuhler and McLachlan (J. Chem. Phys. 107, 5840, 1997), the scheme behind
// NO_SQUISH (Miller et al., J. Chem. Phys. 116, 8649, 2002). The free rotor is split into
// exact rotations about the three principal axes, composed symmetrically
//   x(h/2) y(h/2) z(h) y(h/2) x(h/2),
// each of which rotates the body-frame angular momentum and the orientation exactly. The
// result is time-reversible and symplectic: |L| is kept to round-off, the energy error stays
// bounded (no drift), and the quaternion stays normalised because it is only multiplied by
// unit quaternions. Torques enter as half kicks of the world-frame angular momentum around
// the free rotation (velocity-Verlet style), as in Simulation::step for the spheres.
#include <Eigen/Geometry>
#include <cmath>

#include "dem/core/types.h"

namespace upgrain::dem {

struct RigidRotationState {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> world
  Vec3 angular_momentum_body = Vec3::Zero();  // L in the principal body frame (kg m^2/s)
};

// Exact free rotation about principal axis K for a time h: with L_b,K and I_K fixed, the
// body turns by phi = h L_K / I_K about its axis K, so L_b turns by -phi about that axis.
// `half_step_rate` is h / (2 I_K), so that phi/2 = L_K half_step_rate (no division here).
// One sine and cosine of phi/2 serve both: the quaternion factor (cos phi/2, sin phi/2 e_K)
// and cos phi = c^2 - s^2, sin phi = 2 s c for L_b (the rotation is a fifth of an ellipsoid's
// step cost otherwise, measured with perf).
template <int K>
inline void rotate_about_principal_axis(RigidRotationState& st, double half_step_rate) {
  constexpr int i = (K + 1) % 3, j = (K + 2) % 3;  // (i, j, K) cyclic
  Vec3& l = st.angular_momentum_body;
  const double half = l[K] * half_step_rate;
  double s, c;
  if (std::abs(half) < 1e-4) {
    // The usual DEM step: the next terms, x^5/120 and x^6/720, are below 1e-18 of the result.
    const double x2 = half * half;
    s = half * (1.0 - x2 * (1.0 / 6.0));
    c = 1.0 - x2 * (0.5 - x2 * (1.0 / 24.0));
  } else if (std::abs(half) < 0.03) {
    // A DEM step turns a grain by far less than 0.03 rad: Taylor series to x^7 and x^6,
    // whose remainders (x^9/9!, x^8/8!) are below 2e-17 of the result there, with constant
    // coefficients (no division in the chain: the rotation is latency-bound).
    const double x2 = half * half;
    s = half * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0))));
    c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 - x2 * (1.0 / 720.0)));
  } else {
    s = std::sin(half);
    c = std::cos(half);
  }
  // q <- q (c, s e_K), the Hamilton product written out for a factor with one vector
  // component: (w, v)(c, s e_K) = (c w - s v_K, c v + s w e_K + s v x e_K).
  Eigen::Quaterniond& q = st.orientation;
  const double w = q.w(), vi = q.vec()[i], vj = q.vec()[j], vk = q.vec()[K];
  q.w() = c * w - s * vk;
  q.vec()[i] = c * vi + s * vj;
  q.vec()[j] = c * vj - s * vi;
  q.vec()[K] = c * vk + s * w;
  const double cos_phi = c * c - s * s, sin_phi = 2.0 * s * c;
  const double li = l[i], lj = l[j];
  l[i] = cos_phi * li + sin_phi * lj;
  l[j] = -sin_phi * li + cos_phi * lj;
}

// One step h of torque-free rotation, given the inverse principal moments 1/I (body frame).
inline void free_rotation_step_inverse(RigidRotationState& s, const Vec3& inverse_inertia, double h) {
  const Vec3 rate = (0.5 * h) * inverse_inertia;  // h / (2 I): phi/2 = L rate
  rotate_about_principal_axis<0>(s, 0.5 * rate[0]);
  rotate_about_principal_axis<1>(s, 0.5 * rate[1]);
  rotate_about_principal_axis<2>(s, rate[2]);
  rotate_about_principal_axis<1>(s, 0.5 * rate[1]);
  rotate_about_principal_axis<0>(s, 0.5 * rate[0]);
  // Removes round-off only: every factor is a unit quaternion, so |q|^2 = 1 + e with e of
  // order 1e-16, and one Newton step for 1/sqrt, (3 - |q|^2)/2, normalises to round-off
  // without a square root or a division.
  s.orientation.coeffs() *= 1.5 - 0.5 * s.orientation.squaredNorm();
}

// One step h of torque-free rotation (principal moments `inertia` in the body frame).
inline void free_rotation_step(RigidRotationState& s, const Vec3& inertia, double h) {
  free_rotation_step_inverse(s, inertia.cwiseInverse(), h);
}

// A whole step with a world-frame torque held over it: half kick, free rotation, half kick.
inline void rotation_step(RigidRotationState& s, const Vec3& inertia, const Vec3& torque_world, double h) {
  s.angular_momentum_body += s.orientation.conjugate() * (0.5 * h * torque_world);
  free_rotation_step(s, inertia, h);
  s.angular_momentum_body += s.orientation.conjugate() * (0.5 * h * torque_world);
}

inline Vec3 angular_velocity_world(const RigidRotationState& s, const Vec3& inertia) {
  return s.orientation * s.angular_momentum_body.cwiseQuotient(inertia);
}

inline double rotational_energy(const RigidRotationState& s, const Vec3& inertia) {
  return 0.5 * s.angular_momentum_body.cwiseAbs2().cwiseQuotient(inertia).sum();
}

}  // namespace upgrain::dem
