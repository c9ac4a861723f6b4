#pragma once
// Rotation of a rigid body with a full inertia tensor: the symplectic splitting of
// Dullweber, Leimkuhler and McLachlan (J. Chem. Phys. 107, 5840, 1997), the scheme behind
// NO_SQUISH (Miller et al., J. Chem. Phys. 116, 8649, 2002). The free rotor is split into
// exact rotations about the three principal axes, composed symmetrically
//   x(h/2) y(h/2) z(h) y(h/2) x(h/2),
// each of which rotates the body-frame angular momentum and the orientation exactly. The
// result is time-reversible and symplectic: |L| is kept to round-off, the energy error stays
// bounded (no drift), and the quaternion stays normalised because it is only multiplied by
// unit quaternions. Torques enter as half kicks of the body-frame angular momentum (the world
// torque rotated into the body) around the free rotation (velocity-Verlet style), as in
// Simulation::step for the spheres: rotation_step() here, grain_rotation.cc in the engines.
//
// The arithmetic is written once over "lanes" T: double for one body, or a vector of doubles
// holding several bodies side by side (dem/motion/grain_rotation.cc turns two grains at once).
// Every lane of a vector runs the operations of the scalar code in the same order, so a body
// gets the same bits either way.
#include <Eigen/Geometry>
#include <cmath>

#include "dem/core/types.h"

namespace upgrain::dem {

struct RigidRotationState {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> world
  Vec3 angular_momentum_body = Vec3::Zero();  // L in the principal body frame (kg m^2/s)
};

// A unit quaternion (w, v) and a body-frame angular momentum l, over lanes T.
template <class T>
struct RotorLanes {
  T w;
  T v[3];
  T l[3];
};

// Below this half-angle per principal-axis turn, sine and cosine are their Taylor series to x^3
// and x^4: the next terms, x^5/120 and x^6/720, are below 1e-18 of the result. A DEM step turns a
// grain by far less.
inline constexpr double kSmallHalfAngle = 1e-4;

// q <- q (c, s e_K) and L_b turned by -phi about e_K, given s = sin(phi/2), c = cos(phi/2): one
// sine and cosine of phi/2 serve both, cos phi = c^2 - s^2, sin phi = 2 s c. The Hamilton
// product written out for a factor with one vector component:
// (w, v)(c, s e_K) = (c w - s v_K, c v + s w e_K + s v x e_K).
template <int K, class T>
[[gnu::always_inline]] inline void turn_about_axis(RotorLanes<T>& r, T s, T c) {
  constexpr int i = (K + 1) % 3, j = (K + 2) % 3;  // (i, j, K) cyclic
  const T w = r.w, vi = r.v[i], vj = r.v[j], vk = r.v[K];
  r.w = c * w - s * vk;
  r.v[i] = c * vi + s * vj;
  r.v[j] = c * vj - s * vi;
  r.v[K] = c * vk + s * w;
  const T cos_phi = c * c - s * s, sin_phi = 2.0 * s * c;
  const T li = r.l[i], lj = r.l[j];
  r.l[i] = cos_phi * li + sin_phi * lj;
  r.l[j] = -sin_phi * li + cos_phi * lj;
}

// sin x and cos x by their Taylor series below kSmallHalfAngle, to x^3 and x^4 (any lanes).
template <class T>
[[gnu::always_inline]] inline void small_sine_cosine(T x, T& s, T& c) {
  const T x2 = x * x;
  s = x * (1.0 - x2 * (1.0 / 6.0));
  c = 1.0 - x2 * (0.5 - x2 * (1.0 / 24.0));
}

// Below kModerateHalfAngle: to x^7 and x^6, whose remainders (x^9/9!, x^8/8!) are below 2e-17 of
// the result there, with constant coefficients (no division in the chain).
inline constexpr double kModerateHalfAngle = 0.03;
template <class T>
[[gnu::always_inline]] inline void moderate_sine_cosine(T x, T& s, T& c) {
  const T x2 = x * x;
  s = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0))));
  c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 - x2 * (1.0 / 720.0)));
}

// Exact free rotation about principal axis K: with L_b,K and I_K fixed, the body turns by
// phi = h L_K / I_K about its axis K. `half_step_rate` is h / (2 I_K), so phi/2 = L_K rate.
template <int K>
inline void turn(RotorLanes<double>& r, double half_step_rate) {
  const double half = r.l[K] * half_step_rate;
  double s, c;
  if (std::abs(half) < kSmallHalfAngle) {
    small_sine_cosine(half, s, c);
  } else if (std::abs(half) < kModerateHalfAngle) {
    moderate_sine_cosine(half, s, c);
  } else {
    s = std::sin(half);
    c = std::cos(half);
  }
  turn_about_axis<K>(r, s, c);
}

// Removes round-off only: every factor is a unit quaternion, so |q|^2 = 1 + e with e of order
// 1e-16, and one Newton step for 1/sqrt, (3 - |q|^2)/2, normalises to round-off without a
// square root or a division.
template <class T>
[[gnu::always_inline]] inline void renormalise(RotorLanes<T>& r) {
  const T k = 1.5 - 0.5 * (r.w * r.w + r.v[0] * r.v[0] + r.v[1] * r.v[1] + r.v[2] * r.v[2]);
  r.w *= k;
  r.v[0] *= k;
  r.v[1] *= k;
  r.v[2] *= k;
}

// One step h of torque-free rotation, `rate` = (h/2) / I per principal axis: x(h/2) y(h/2) z(h)
// y(h/2) x(h/2).
inline void free_rotation(RotorLanes<double>& r, const double rate[3]) {
  turn<0>(r, 0.5 * rate[0]);
  turn<1>(r, 0.5 * rate[1]);
  turn<2>(r, rate[2]);
  turn<1>(r, 0.5 * rate[1]);
  turn<0>(r, 0.5 * rate[0]);
  renormalise(r);
}

// out = R(q) a for a unit quaternion q = (w, v), or R(q)^T a with Inverse (v -> -v):
// a + 2w (v x a) + 2 v x (v x a).
template <bool Inverse, class T>
[[gnu::always_inline]] inline void rotate_vector(T w, const T v_in[3], const T a[3], T out[3]) {
  const T v[3] = {Inverse ? -v_in[0] : v_in[0], Inverse ? -v_in[1] : v_in[1], Inverse ? -v_in[2] : v_in[2]};
  const T c0 = 2.0 * (v[1] * a[2] - v[2] * a[1]);
  const T c1 = 2.0 * (v[2] * a[0] - v[0] * a[2]);
  const T c2 = 2.0 * (v[0] * a[1] - v[1] * a[0]);
  out[0] = a[0] + w * c0 + (v[1] * c2 - v[2] * c1);
  out[1] = a[1] + w * c1 + (v[2] * c0 - v[0] * c2);
  out[2] = a[2] + w * c2 + (v[0] * c1 - v[1] * c0);
}

// One step h of torque-free rotation, given the inverse principal moments 1/I (body frame).
inline void free_rotation_step_inverse(RigidRotationState& s, const Vec3& inverse_inertia, double h) {
  RotorLanes<double> r{
      s.orientation.w(),
      {s.orientation.x(), s.orientation.y(), s.orientation.z()},
      {s.angular_momentum_body.x(), s.angular_momentum_body.y(), s.angular_momentum_body.z()}};
  const double rate[3] = {0.5 * h * inverse_inertia[0], 0.5 * h * inverse_inertia[1],
                          0.5 * h * inverse_inertia[2]};
  free_rotation(r, rate);
  s.orientation = Eigen::Quaterniond(r.w, r.v[0], r.v[1], r.v[2]);
  s.angular_momentum_body = Vec3(r.l[0], r.l[1], r.l[2]);
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
