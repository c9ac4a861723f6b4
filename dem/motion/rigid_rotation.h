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

#include "dem/core/types.h"

namespace upgrain::dem {

struct RigidRotationState {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> world
  Vec3 angular_momentum_body = Vec3::Zero();  // L in the principal body frame (kg m^2/s)
};

// Exact free rotation about principal axis k for a time h: with L_b,k and I_k fixed, the
// body turns by phi = h L_k / I_k about its axis k, so L_b turns by -phi about that axis.
inline void rotate_about_principal_axis(RigidRotationState& s, const Vec3& inertia, int k, double h) {
  const double phi = h * s.angular_momentum_body[k] / inertia[k];
  const Eigen::AngleAxisd turn(phi, Vec3::Unit(k));
  s.orientation = s.orientation * Eigen::Quaterniond(turn);
  s.angular_momentum_body = turn.inverse() * s.angular_momentum_body;
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
