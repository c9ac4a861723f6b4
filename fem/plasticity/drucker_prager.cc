#include "fem/plasticity/drucker_prager.h"

#include <cmath>

namespace upgrain::fem {

namespace {

// sqrt(J2) of a deviator s in Mandel notation: J2 = s:s / 2.
double sqrt_j2(const Vec6& deviator) { return std::sqrt(0.5 * deviator.squaredNorm()); }

// The cone through the triaxial-compression (sign -1) or -extension (sign +1) corners of
// the Mohr–Coulomb hexagon (de Souza Neto et al. 2008, sect. 6.4):
// eta = 6 sin / (sqrt3 (3 -+ sin)), xi = 6 cos / (sqrt3 (3 -+ sin)).
struct ConeCoefficients {
  double eta, xi;
};
ConeCoefficients corner_match(double angle, double sign) {
  const double d = std::sqrt(3.0) * (3.0 + sign * std::sin(angle));
  return {6.0 * std::sin(angle) / d, 6.0 * std::cos(angle) / d};
}

}  // namespace

double DruckerPrager::yield_function(const Vec6& stress) const {
  return sqrt_j2(mandel::deviator(stress)) + eta * mandel::trace(stress) / 3.0 - xi * cohesion;
}

DruckerPrager match_mohr_coulomb(double phi, double psi, double c, ConeMatching matching) {
  DruckerPrager dp;
  dp.cohesion = c;
  switch (matching) {
    case ConeMatching::outer:
    case ConeMatching::inner: {
      const double sign = matching == ConeMatching::outer ? -1.0 : 1.0;
      const ConeCoefficients yield = corner_match(phi, sign);
      dp.eta = yield.eta;
      dp.xi = yield.xi;
      dp.eta_bar = corner_match(psi, sign).eta;
      break;
    }
    case ConeMatching::plane_strain: {
      // Plastic plane strain (d eps^p_33 = 0) fixes the out-of-plane stress relative to
      // Mohr's circle of the plane (docs/fem.md, "Cone matching"). There Psi's dilatancy
      // d eps^p_v / (d eps^p_1 - d eps^p_3) equals Mohr–Coulomb's sin psi for
      // eta_bar = 3 tan psi / sqrt(9 + 12 tan^2 psi), and Phi = 0 coincides with
      // t + m sin phi = c cos phi (t, m the radius and centre of Mohr's circle) for the eta
      // and xi below. With psi = phi they are de Souza Neto et al.'s plane-strain match,
      // eta = 3 tan phi / sqrt(9 + 12 tan^2 phi), xi = 3 / sqrt(9 + 12 tan^2 phi).
      const double t = std::tan(psi);
      dp.eta_bar = 3.0 * t / std::sqrt(9.0 + 12.0 * t * t);
      const double root = std::sqrt(3.0 * (3.0 - dp.eta_bar * dp.eta_bar));
      dp.eta = 3.0 * std::sin(phi) / (root + dp.eta_bar * std::sin(phi));
      dp.xi = std::cos(phi) * (3.0 - dp.eta * dp.eta_bar) / root;
      break;
    }
  }
  return dp;
}

ReturnMapping return_map(const DruckerPrager& cone, const Elasticity& el, const Vec6& trial) {
  const double G = el.shear_modulus, K = el.bulk_modulus;
  ReturnMapping r;
  const Vec6 s_trial = mandel::deviator(trial);
  const double p_trial = mandel::trace(trial) / 3.0;
  const double q_trial = sqrt_j2(s_trial);
  const double phi_trial = q_trial + cone.eta * p_trial - cone.xi * cone.cohesion;
  if (phi_trial <= 0.0) {
    r.stress = trial;
    r.tangent = el.stiffness();
    return r;
  }

  // Return to the smooth cone (de Souza Neto et al. 2008, sect. 8.3, with H = 0): the
  // consistency condition is linear in Delta gamma because s keeps its direction.
  const double A = 1.0 / (G + K * cone.eta * cone.eta_bar);
  const double dgamma = phi_trial * A;
  if (q_trial - G * dgamma >= 0.0 && q_trial > 0.0) {
    r.region = ReturnRegion::cone;
    r.plastic_multiplier = dgamma;
    const double factor = 1.0 - G * dgamma / q_trial;
    const double p = p_trial - K * cone.eta_bar * dgamma;
    r.stress = factor * s_trial + p * mandel::identity();
    // Consistent tangent (de Souza Neto et al. 2008, sect. 8.3, with H = 0), with n the unit
    // deviatoric flow direction s_trial / |s_trial| and |s_trial| = sqrt2 sqrt(J2_trial):
    //   D = 2G (1 - G dgamma / q) I_dev + 2G (G dgamma / q - G A) n (x) n
    //       - sqrt2 G A K (eta n (x) 1 + eta_bar 1 (x) n) + K (1 - K eta eta_bar A) 1 (x) 1.
    // The eta term comes from d(Delta gamma)/d eps (the yield function), the eta_bar term
    // from the pressure update (the potential): hence the asymmetry when they differ.
    const Vec6 n = s_trial / s_trial.norm();
    const Vec6 one = mandel::identity();
    r.tangent =
        2.0 * G * factor * mandel::deviatoric_projector() +
        2.0 * G * (G * dgamma / q_trial - G * A) * n * n.transpose() -
        mandel::sqrt2 * G * A * K * (cone.eta * n * one.transpose() + cone.eta_bar * one * n.transpose()) +
        K * (1.0 - K * cone.eta * cone.eta_bar * A) * one * one.transpose();
    return r;
  }

  // Return to the apex (de Souza Neto et al. 2008, sect. 8.3, with H = 0): the
  // stress is the apex whatever the strain, so the tangent is zero.
  r.region = ReturnRegion::apex;
  r.stress = cone.apex_pressure() * mandel::identity();
  r.tangent.setZero();
  r.plastic_multiplier = dgamma;
  return r;
}

}  // namespace upgrain::fem
