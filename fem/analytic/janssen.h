#pragma once
// Janssen's slab solution for a granular fill in a vertical box with wall friction
// (Janssen 1895, Z. Ver. Dtsch. Ing. 39:1045; English translation Sperl 2006, Granular
// Matter 8:59). Plain C++ (docs/fem.md, "Janssen's solution").
//
// A horizontal slice of area A at depth d below the free surface carries the mean vertical
// stress sigma_v(d) (compression positive here). The walls press on it with K sigma_v and,
// where they slip, hold it up with mu_i K sigma_v per unit length of wall i. Equilibrium of
// the slice, A d sigma_v / dd = rho g A - K sigma_v sum_i mu_i L_i, with sigma_v(0) = 0:
//   sigma_v(d) = rho g A / (K F) (1 - exp(-K F d / A)),    F = sum_i mu_i L_i,
// the friction-weighted perimeter. For a square box of side D with one mu_w, A/F = D/(4 mu_w)
// and this is sigma_v = rho g D / (4 mu_w K) (1 - exp(-4 mu_w K d / D)). Its assumptions:
// sigma_v uniform across the slice, K constant, and full friction mobilised on every wall
// (the walls slip everywhere). As F -> 0 it tends to the hydrostatic rho g d.
#include <cmath>

namespace upgrain::fem {

struct JanssenColumn {
  double unit_weight = 0.0;         // rho g (N/m^3)
  double area = 0.0;                // A (m^2)
  double friction_perimeter = 0.0;  // F = sum of mu_i L_i over the walls (m)
  double lateral_ratio = 0.0;       // K = sigma_h / sigma_v at the wall
  double height = 0.0;              // fill height H (m)

  // A / (K F), the decay length of the exponential (infinite without friction).
  [[nodiscard]] double decay_length() const { return area / (lateral_ratio * friction_perimeter); }

  // sigma_v at depth d >= 0 below the free surface, compression positive.
  [[nodiscard]] double vertical_pressure(double depth) const {
    const double x = depth / decay_length();
    // -expm1 keeps full precision where x is small (weak friction, shallow depth).
    return x == 0.0 ? unit_weight * depth : -unit_weight * decay_length() * std::expm1(-x);
  }
  // The same in the project's convention (compression negative), at height z above the floor.
  [[nodiscard]] double vertical_stress(double z) const { return -vertical_pressure(height - z); }

  // Mean of sigma_zz over the slab z0 < z < z1 (exact integral of the profile).
  [[nodiscard]] double mean_vertical_stress(double z0, double z1) const {
    const double L = decay_length();
    if (!std::isfinite(L)) return -unit_weight * (height - 0.5 * (z0 + z1));
    // int_{d0}^{d1} rho g L (1 - exp(-d/L)) dd = rho g L (d1 - d0 + L (exp(-d1/L) - exp(-d0/L))).
    const double d0 = height - z1, d1 = height - z0;
    return -unit_weight * L * (d1 - d0 + L * (std::expm1(-d1 / L) - std::expm1(-d0 / L))) / (d1 - d0);
  }

  // Share of the fill's weight the walls carry: 1 - sigma_v(H) A / (rho g A H).
  [[nodiscard]] double wall_share() const { return 1.0 - vertical_pressure(height) / (unit_weight * height); }
};

}  // namespace upgrain::fem
