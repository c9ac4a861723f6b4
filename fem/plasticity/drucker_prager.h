#pragma once
// Drucker–Prager perfect plasticity at a material point, small strain (docs/fem.md,
// "Drucker–Prager elastoplasticity"). Plain C++ and Eigen: the return mapping and its
// consistent tangent are tested without MPI, files or deal.II.
//
// Yield function and plastic potential (de Souza Neto, Perić & Owen 2008, Computational
// Methods for Plasticity, sect. 6.4; tension positive, which is the project's convention of
// compression negative):
//   Phi(sigma) = sqrt(J2(s)) + eta p - xi c,     Psi(sigma) = sqrt(J2(s)) + eta_bar p,
// with p = tr(sigma)/3, s = dev(sigma), J2 = s:s/2. eta = eta_bar is associated flow;
// eta_bar < eta (a dilatancy angle psi < phi) is non-associated.
#include "fem/plasticity/cone_matching.h"
#include "fem/plasticity/mandel.h"

namespace upgrain::fem {

struct DruckerPrager {
  double eta = 0.0;       // friction coefficient of Phi
  double eta_bar = 0.0;   // dilatancy coefficient of Psi
  double xi = 0.0;        // cohesion factor of Phi
  double cohesion = 0.0;  // c (Pa)

  [[nodiscard]] double yield_function(const Vec6& stress) const;
  // Mean stress of the apex, where the cone meets the hydrostatic axis: p = xi c / eta.
  [[nodiscard]] double apex_pressure() const { return xi * cohesion / eta; }
};

// The cone of a Mohr–Coulomb material: friction angle phi, dilatancy angle psi (radians,
// 0 <= psi <= phi < pi/2) and cohesion c (Pa).
DruckerPrager match_mohr_coulomb(double friction_angle, double dilatancy_angle, double cohesion,
                                 ConeMatching matching);

enum class ReturnRegion { elastic, cone, apex };

struct ReturnMapping {
  Vec6 stress = Vec6::Zero();
  // d sigma_{n+1} / d eps_{n+1}, the consistent (algorithmic) tangent of the backward
  // Euler update (Simo & Taylor 1985; de Souza Neto et al. 2008, sect. 8.3). Not
  // symmetric for non-associated flow; zero at the apex of a perfectly plastic cone.
  Mat6 tangent = Mat6::Zero();
  ReturnRegion region = ReturnRegion::elastic;
  double plastic_multiplier = 0.0;  // Delta gamma of the cone return; 0 when elastic
};

// Backward Euler (closest-point for associated flow) return of an elastic trial stress
// sigma_trial = sigma_n + C : (eps_{n+1} - eps_n) onto the cone, in closed form (de Souza
// Neto et al. 2008, sect. 8.3, with zero hardening):
// - elastic if Phi(sigma_trial) <= 0: sigma = sigma_trial, tangent C;
// - cone: Delta gamma = Phi(sigma_trial) / (G + K eta eta_bar),
//         s = (1 - G Delta gamma / sqrt(J2_trial)) s_trial, p = p_trial - K eta_bar Delta gamma,
//   valid while the factor of s stays >= 0;
// - apex otherwise: sigma = (xi c / eta) 1.
ReturnMapping return_map(const DruckerPrager& cone, const Elasticity& elasticity, const Vec6& trial_stress);

}  // namespace upgrain::fem
