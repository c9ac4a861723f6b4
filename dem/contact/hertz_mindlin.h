#pragma once
// Scalar kernels of the Hertz-Mindlin contact law. Each is a plain function of a few
// numbers so tests can call it directly. Equations: docs/contact-law.md.
#include <cmath>

namespace upgrain::dem::hertz {

// Radius of the contact circle a = sqrt(R* delta) (Johnson 1985, eq. 4.22). The force, the
// stiffnesses and the energy of a contact all follow from it; the force loop works it out once.
inline double contact_radius(double r_star, double delta) { return std::sqrt(r_star * delta); }

// Hertz normal force F = 4/3 E* a delta = 4/3 E* sqrt(R*) delta^(3/2)  (Johnson 1985, eq. 4.23).
inline double normal_force_at(double e_star, double a, double delta) {
  return 4.0 / 3.0 * e_star * a * delta;
}
inline double normal_force(double e_star, double r_star, double delta) {
  return normal_force_at(e_star, contact_radius(r_star, delta), delta);
}

// Tangent normal stiffness k_n = dF/d(delta) = 2 E* sqrt(R* delta) = 2 E* a.
inline double normal_stiffness_at(double e_star, double a) { return 2.0 * e_star * a; }
inline double normal_stiffness(double e_star, double r_star, double delta) {
  return normal_stiffness_at(e_star, contact_radius(r_star, delta));
}

// Elastic energy stored in the normal spring, the integral of F: 8/15 E* sqrt(R*) delta^(5/2).
inline double normal_energy(double e_star, double r_star, double delta) {
  return 8.0 / 15.0 * e_star * std::sqrt(r_star) * delta * delta * std::sqrt(delta);
}

// Mindlin no-slip tangential stiffness k_t = 8 G* a, a = sqrt(R* delta)
// (Mindlin 1949; Di Renzo and Di Maio 2004, eq. 8).
inline double tangential_stiffness_at(double g_star, double a) { return 8.0 * g_star * a; }
inline double tangential_stiffness(double g_star, double r_star, double delta) {
  return tangential_stiffness_at(g_star, contact_radius(r_star, delta));
}

// Normal viscous damping coefficient c_n = 2 zeta sqrt(m* k_n) (Yan and Regueiro eq. 21-22, docs/stress.md),
// with m* = m1 m2 / (m1 + m2) and k_n the tangent Hertz stiffness above.
inline double damping_coefficient(double zeta, double m_star, double k_n) {
  return 2.0 * zeta * std::sqrt(m_star * k_n);
}

// Duration of an undamped Hertz impact at relative normal speed v
// (Johnson 1985, eq. 11.24): t = 2.868 (m*^2 / (R* E*^2 v))^(1/5).
inline double contact_duration(double e_star, double r_star, double m_star, double v) {
  // 2 I (15/16)^(2/5) with I = integral_0^1 (1 - x^(5/2))^(-1/2) dx = (2/5) B(2/5, 1/2): Johnson's
  // 2.87 to 16 digits (2.8683 left an error of 1.2e-5, which the time-step study resolves).
  constexpr double kHertzDuration = 2.8682656991953315;
  return kHertzDuration * std::pow(m_star * m_star / (r_star * e_star * e_star * v), 0.2);
}

// Static overlap of a Hertz contact carrying the force F: inverse of normal_force.
inline double overlap_for_force(double e_star, double r_star, double force) {
  return std::pow(3.0 * force / (4.0 * e_star * std::sqrt(r_star)), 2.0 / 3.0);
}

}  // namespace upgrain::dem::hertz
