#pragma once
// Elastic and frictional properties and the effective (pair) quantities of Hertz-Mindlin
// contact mechanics (Johnson 1985, Contact Mechanics, ch. 4 and 7; Di Renzo and Di Maio
// 2004, Chem. Eng. Sci. 59:525).
#include <cmath>

namespace upgrain::dem {

struct Material {
  double density = 2650.0;       // kg/m^3
  double youngs_modulus = 29e9;  // Pa
  double poisson_ratio = 0.25;   // -

  [[nodiscard]] double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
};

// 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 (Johnson eq. 4.22).
inline double effective_youngs_modulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

// 1/G* = (2-nu1)/G1 + (2-nu2)/G2 (Mindlin 1949; Di Renzo and Di Maio 2004, eq. 9).
inline double effective_shear_modulus(const Material& a, const Material& b) {
  return 1.0 / ((2.0 - a.poisson_ratio) / a.shear_modulus() + (2.0 - b.poisson_ratio) / b.shear_modulus());
}

// The parameters of the contact parts every law shares (dem/contact/law/contact_law.h): the
// Coulomb coefficient between grains (a wall has its own, PlaneWall::friction) and the normal
// dashpot's damping ratio. A law's own constants are its normal part's `Constants`
// (dem/contact/law/).
struct ContactMaterial {
  double friction_pp = 0.5;    // Coulomb coefficient between particles
  double damping_ratio = 0.5;  // zeta in c_n = 2 zeta sqrt(m* k_n), Yan and Regueiro eq. (21), docs/stress.md
};

}  // namespace upgrain::dem
