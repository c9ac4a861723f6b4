#pragma once
// The local rheology of dense granular flow from steady simple shear at a constant normal
// stress P (docs/element-tests.md, "Simple shear and mu(I)"). Each steady state gives the
// inertial number I = gamma_dot d / sqrt(P / rho), the friction coefficient mu = tau / P and the
// solid fraction phi (GDR MiDi 2004, Eur. Phys. J. E 14, 341-365). Fitted here:
//   mu(I) = mu_s + (mu_2 - mu_s) / (1 + I0 / I)
//     (Jop, Forterre & Pouliquen 2006, Nature 441, 727-730; the form of GDR MiDi 2004);
//   phi(I) = phi_max - b I
//     (da Cruz, Emam, Prochnow, Roux & Chevoir 2005, Phys. Rev. E 72, 021309: linear in I
//     over the dense regime).
// Plain functions over plain numbers.
#include <span>

namespace upgrain::dem {

struct MuOfI {
  double mu_s = 0.0;  // the quasi-static limit, I -> 0
  double mu_2 = 0.0;  // the limit I -> infinity
  double i0 = 0.0;    // the inertial number half way between them
  double rms = 0.0;   // the root-mean-square residual of mu
  // I0 at an end of the range searched (a tenth of the smallest I, ten times the largest): the
  // data do not bound it, and mu_2, I0 are then a straight line's, not the curve's.
  bool i0_at_bound = false;
  [[nodiscard]] double operator()(double i) const { return mu_s + (mu_2 - mu_s) / (1.0 + i0 / i); }
};

// Least squares of mu over (mu_s, mu_2, I0): for a given I0 the model is linear in mu_s and mu_2
// (mu = mu_s (1 - w) + mu_2 w, w = I / (I + I0)), solved exactly; I0 is searched on a
// logarithmic grid over [min I / 10, 10 max I], then refined by golden sections around the best
// grid point. Throws upgrain::Error for fewer than three points, an I <= 0, sizes that differ,
// or fewer than three distinct I.
MuOfI fit_mu_of_i(std::span<const double> inertial_numbers, std::span<const double> friction);

struct PhiOfI {
  double phi_max = 0.0;  // phi at I -> 0
  double slope = 0.0;    // b in phi = phi_max - b I
  double rms = 0.0;
  [[nodiscard]] double operator()(double i) const { return phi_max - slope * i; }
};

// The least-squares line of phi against I. Throws upgrain::Error for fewer than two distinct I.
PhiOfI fit_phi_of_i(std::span<const double> inertial_numbers, std::span<const double> solid_fraction);

}  // namespace upgrain::dem
