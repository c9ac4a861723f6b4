#pragma once
// The exact solution of a laterally confined (oedometric) elastic column under its own
// weight: the continuum counterpart of a granular bed deposited in a box with frictionless
// walls. Plain C++, no deal.II, so that tests and the DEM comparison can use it directly.
//
// Boundary value problem (docs/fem.md, "The analytic solution"): domain [0,Lx]x[0,Ly]x[0,H],
// body force (0,0,-rho g), floor u_z = 0, side walls u_n = 0 (rollers), top traction free.
// The ansatz u = (0, 0, w(z)) gives eps_zz = w' as the only strain, hence
//   sigma_zz = M w',  sigma_xx = sigma_yy = lambda w' = K0 sigma_zz,  no shear,     (1)
// with the constrained (oedometric) modulus M = lambda + 2 mu = E(1-nu)/((1+nu)(1-2nu))
// and K0 = lambda/(lambda + 2 mu) = nu/(1-nu). Equilibrium d(sigma_zz)/dz = rho g and the
// free top sigma_zz(H) = 0 give
//   sigma_zz(z) = -rho g (H - z),                                                      (2)
// and w(0) = 0 with w' = sigma_zz / M gives
//   u_z(z) = -(rho g / M) (H z - z^2/2).                                               (3)
// The rollers carry no shear, which (1) satisfies, so (1)-(3) solve the BVP exactly.
// Sign convention: compression negative.
#include <cmath>

namespace upgrain::fem {

// Lateral earth-pressure coefficient at rest of an isotropic elastic medium under uniaxial
// strain: K0 = sigma_xx / sigma_zz = nu / (1 - nu).
inline double analytic_k0(double poisson_ratio) { return poisson_ratio / (1.0 - poisson_ratio); }

struct ConfinedColumn {
  double unit_weight = 0.0;     // rho g (N/m^3)
  double height = 0.0;          // fill height H (m)
  double youngs_modulus = 0.0;  // E (Pa)
  double poisson_ratio = 0.0;   // nu (-)

  // Lame's first parameter lambda = E nu / ((1+nu)(1-2nu)) and shear modulus mu = E/(2(1+nu)).
  [[nodiscard]] double lame_lambda() const {
    return youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  [[nodiscard]] double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  // Constrained (oedometric) modulus M = lambda + 2 mu.
  [[nodiscard]] double constrained_modulus() const {
    return youngs_modulus * (1.0 - poisson_ratio) / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  [[nodiscard]] double k0() const { return analytic_k0(poisson_ratio); }

  // Eq. (2): sigma_zz at height z; sigma_xx = sigma_yy = k0() * vertical_stress(z).
  [[nodiscard]] double vertical_stress(double z) const { return -unit_weight * (height - z); }
  // Eq. (3).
  [[nodiscard]] double vertical_displacement(double z) const {
    return -(unit_weight / constrained_modulus()) * (height * z - 0.5 * z * z);
  }
  // Mean of sigma_zz over the slab z0 < z < z1: sigma_zz is linear in z, so it is the value
  // at the slab's mid-height.
  [[nodiscard]] double mean_vertical_stress(double z0, double z1) const {
    return vertical_stress(0.5 * (z0 + z1));
  }

  // L2 norms over a column of footprint area A, used to turn the solver's absolute errors
  // into relative ones:
  //   ||u||^2 = A (rho g/M)^2 int_0^H (H z - z^2/2)^2 dz = A (rho g/M)^2 (2/15) H^5,
  //   ||sigma||^2 (Frobenius) = A (1 + 2 K0^2) (rho g)^2 int_0^H (H - z)^2 dz
  //                           = A (1 + 2 K0^2) (rho g)^2 H^3 / 3.
  [[nodiscard]] double displacement_l2_norm(double area) const {
    return unit_weight / constrained_modulus() * std::sqrt(area * 2.0 / 15.0 * std::pow(height, 5));
  }
  [[nodiscard]] double stress_l2_norm(double area) const {
    const double k = k0();
    return unit_weight * std::sqrt(area * (1.0 + 2.0 * k * k) * std::pow(height, 3) / 3.0);
  }
};

}  // namespace upgrain::fem
