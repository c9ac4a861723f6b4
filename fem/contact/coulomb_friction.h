#pragma once
// Coulomb friction at a point of a rigid wall, regularised by a tangential penalty
// (Wriggers 2006, Computational Contact Mechanics, 2nd ed., ch. 5; Laursen 2002,
// Computational Contact and Impact Mechanics): the elastic predictor and return of the slip
// law, the friction counterpart of a plastic return mapping (Simo & Hughes 1998). Plain C++
// and Eigen (docs/fem.md, "Frictional walls").
//
// The wall is fixed and its normal displacement is held, so the tangential gap is the
// tangential displacement of the body, g_T = (1 - n (x) n) u. With t_n the traction the
// wall exerted on the body at the last converged step and Delta g_T the tangential
// displacement since then:
//   trial   t* = t_n - eps_T Delta g_T                 (stick: an elastic tangential spring)
//   stick   |t*| <  mu p:  t = t*
//   slip    |t*| >= mu p:  t = mu p t* / |t*|          (opposes the slip, magnitude mu p)
// with p = max(0, -sigma_nn) the normal pressure and eps_T the penalty (N/m^3). As
// eps_T -> infinity the stick branch tends to no slip at all; in the slip branch t does not
// depend on eps_T.
#include <Eigen/Core>
#include <algorithm>

namespace upgrain::fem {

struct FrictionResponse {
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();  // on the body, tangential
  // d t / d u (through g_T; includes the projection onto the wall's plane) and d t / d p.
  Eigen::Matrix3d d_traction_d_displacement = Eigen::Matrix3d::Zero();
  Eigen::Vector3d d_traction_d_pressure = Eigen::Vector3d::Zero();
  bool slipping = false;
};

// normal: unit outward normal of the body at the wall; previous_traction: t_n (tangential);
// slip_increment: displacement increment since step n (its normal part is ignored);
// pressure: -sigma_nn (compression positive; <= 0 means no friction can act).
inline FrictionResponse coulomb_friction(const Eigen::Vector3d& normal,
                                         const Eigen::Vector3d& previous_traction,
                                         const Eigen::Vector3d& slip_increment, double pressure,
                                         double friction_coefficient, double penalty) {
  const Eigen::Matrix3d tangential = Eigen::Matrix3d::Identity() - normal * normal.transpose();
  const Eigen::Vector3d trial = tangential * (previous_traction - penalty * slip_increment);
  const double limit = friction_coefficient * std::max(pressure, 0.0);
  const double magnitude = trial.norm();
  FrictionResponse r;
  // Strictly below the limit: with no pressure (limit 0) and no trial traction, as at the
  // start of loading, the point slips with zero traction rather than sticking, so that
  // Newton's method starts from the frictionless state, not from walls glued at zero load.
  if (magnitude < limit) {
    r.traction = trial;
    r.d_traction_d_displacement = -penalty * tangential;
    return r;
  }
  r.slipping = true;
  if (magnitude == 0.0) return r;  // no pressure and no trial traction: nothing acts
  const Eigen::Vector3d direction = trial / magnitude;
  r.traction = limit * direction;
  // d(t* / |t*|) = (1 - e (x) e) d t* / |t*| with d t* = -eps_T (1 - n (x) n) du.
  r.d_traction_d_displacement =
      -penalty * limit / magnitude * (tangential - direction * direction.transpose()) * tangential;
  if (pressure > 0.0) r.d_traction_d_pressure = friction_coefficient * direction;
  return r;
}

}  // namespace upgrain::fem
