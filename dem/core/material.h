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

// Rigid, frictional walls are modelled with the particles' own material: a plane of
// the same E and nu (the convention of LIGGGHTS' wall/gran). Documented in
// docs/contact-law.md.
struct ContactMaterial {
  double e_star_pp = 0.0;  // effective Young's modulus particle-particle
  double g_star_pp = 0.0;  // effective shear modulus particle-particle
  double e_star_pw = 0.0;  // particle-wall
  double g_star_pw = 0.0;
  double friction_pp = 0.5;    // Coulomb coefficient between particles
  double damping_ratio = 0.5;  // zeta in c_n = 2 zeta sqrt(m* k_n), Yan and Regueiro eq. (21), docs/stress.md
  // Linear laws (dem/contact/law/hooke.h): spring constants (N/m), particle-particle and
  // particle-wall alike; set by the law from the scene.
  double k_n = 0.0;
  double k_t = 0.0;

  static ContactMaterial from(const Material& m, double friction_pp, double damping_ratio) {
    ContactMaterial c;
    c.e_star_pp = effective_youngs_modulus(m, m);
    c.g_star_pp = effective_shear_modulus(m, m);
    c.e_star_pw = c.e_star_pp;
    c.g_star_pw = c.g_star_pp;
    c.friction_pp = friction_pp;
    c.damping_ratio = damping_ratio;
    return c;
  }
};

}  // namespace upgrain::dem
