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

// Exact free rotation about principal axis k for a time h: with L_b,k and I_k fixed, the
// body turns by phi = h L_k / I_k about its axis k, so L_b turns by -phi about that axis.
// One sine and cosine of phi/2 serve both: the quaternion factor (cos phi/2, sin phi/2 e_k)
// and cos phi = c^2 - s^2, sin phi = 2 s c for L_b (the rotation is a fifth of an ellipsoid's
// step cost otherwise, measured with perf).
inline void rotate_about_principal_axis(RigidRotationState& st, const Vec3& inertia, int k, double h) {
  const double half = 0.5 * h * st.angular_momentum_body[k] / inertia[k];
  double s, c;
  if (std::abs(half) < 0.03) {
    // A DEM step turns a grain by far less than 0.03 rad: Taylor series to x^9 and x^8, whose
    // remainders (x^11/11!, x^10/10!) are below 1e-16 of the result there, at a fifth of the
    // cost of sincos.
    const double x2 = half * half;
    s = half * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))));
    c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0)));
  } else {
    s = std::sin(half);
    c = std::cos(half);
  }
  Eigen::Quaterniond turn(c, 0.0, 0.0, 0.0);
  turn.vec()[k] = s;
  st.orientation = st.orientation * turn;
  const double cos_phi = c * c - s * s, sin_phi = 2.0 * s * c;
  const int i = (k + 1) % 3, j = (k + 2) % 3;  // (i, j, k) cyclic
  Vec3& l = st.angular_momentum_body;
  const double li = l[i], lj = l[j];
  l[i] = cos_phi * li + sin_phi * lj;
  l[j] = -sin_phi * li + cos_phi * lj;
}

// One step h of torque-free rotation (principal moments `inertia` in the body frame).
inline void free_rotation_step(RigidRotationState& s, const Vec3& inertia, double h) {
  rotate_about_principal_axis(s, inertia, 0, 0.5 * h);
  rotate_about_principal_axis(s, inertia, 1, 0.5 * h);
  rotate_about_principal_axis(s, inertia, 2, h);
  rotate_about_principal_axis(s, inertia, 1, 0.5 * h);
  rotate_about_principal_axis(s, inertia, 0, 0.5 * h);
  s.orientation.normalize();  // removes round-off only: every factor is a unit quaternion
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
