#pragma once
// Rolling resistance of one contact: the elastic-plastic spring-dashpot model ("type C") of
// Iwashita and Oda (1998, J. Eng. Mech. 124:285) as assessed by Ai, Chen, Rotter and Ooi
// (2011, Powder Technol. 206:269), the model LIGGGHTS calls `rolling_friction epsd2`, with
// the dashpot of Ai et al. Incremental, like the Mindlin spring of contact_response.h: the
// spring torque is carried per contact and turned with the contact plane. Equations and
// choices (rolling radius of ellipsoids, inertia of the dashpot): docs/contact-law.md.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem/contact/contact_parameters.h"
#include "dem/core/contact_history.h"
#include "dem/core/types.h"

namespace upgrain::dem {

struct RollingParameters {
  double friction = 0.0;       // mu_r: plastic limit |M_r| <= mu_r R* F_n
  double damping_ratio = 0.0;  // eta_r: dashpot C_r = eta_r 2 sqrt(I_r k_r), rolling and twisting
  // Twisting resistance: G_tw of the no-slip torsion stiffness 16/3 G_tw a^3, with
  // 1/G_tw = 1/G_1 + 1/G_2 (Johnson 1985, 7.4); 0: no twisting resistance.
  double twisting_modulus = 0.0;
};

// The parameters of a scene of one material (E, nu) for grains and walls; `twisting`: with
// twisting resistance.
inline RollingParameters rolling_parameters(double mu_r, double eta_r, bool twisting, double youngs_modulus,
                                            double poisson_ratio) {
  const double shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  return {mu_r, eta_r, twisting ? 0.5 * shear_modulus : 0.0};
}

// Rolling stiffness k_r = 2.25 k_n mu_r^2 R*^2 (Iwashita and Oda 1998; Ai et al. 2011),
// with k_n the tangent Hertz stiffness 2 E* sqrt(R* delta).
inline double rolling_stiffness(double k_n, double mu_r, double r_star) {
  return 2.25 * k_n * mu_r * mu_r * r_star * r_star;
}

// One contact as the rolling resistance sees it.
struct RollingContact {
  Vec3 normal;      // unit contact normal
  Vec3 omega_rel;   // omega_i - omega_j
  double r_star;    // rolling radius
  double k_n;       // the law's tangent normal stiffness
  double f_n;       // normal force after the dashpot and the clamp: the plastic limit's scale
  double inertia;   // the pair's rolling inertia I_r (for the dashpot)
  double dt;        // time step
  double overlap;   // delta, for the contact radius a = sqrt(R* delta) of the twisting spring
  double friction;  // the contact's Coulomb coefficient: the twisting spring's slip limit
};

// Twisting resistance of one contact: the torsion of a Hertz contact circle of radius
// a = sqrt(R* delta) (Lubkin 1951; Deresiewicz 1954; Johnson 1985, 7.4). Without slip the
// torque is M = 16/3 G_tw a^3 theta; with full slip over the circle under Hertz's pressure it
// is 3 pi/16 mu a F_n. Regularised, as the Mindlin spring, by an incremental spring of the
// no-slip stiffness capped at the full-slip torque, with the rolling dashpot's damping ratio.
// Returns the spring's torque about n on body i; `viscous` receives the dashpot's.
template <bool Energy>
[[gnu::always_inline]] inline double twisting_resistance(const RollingParameters& p, const RollingContact& c,
                                                         RollingSpring& s, ContactEnergy& energy,
                                                         double& viscous) {
  const double a = std::sqrt(c.r_star * std::max(c.overlap, 0.0));
  const double k = (16.0 / 3.0) * p.twisting_modulus * a * a * a;
  double& m = s.twist;
  viscous = 0.0;
  if (!(k > 0.0)) {
    m = 0.0;
    return 0.0;
  }
  if constexpr (Energy) {
    if (s.twist_stiffness > 0.0)
      energy.rolling_stiffness_change += 0.5 * m * m * (1.0 / k - 1.0 / s.twist_stiffness);
  }
  const double before = m;
  const double w_t = c.omega_rel.dot(c.normal);  // relative spin about the normal
  m -= k * c.dt * w_t;
  s.twist_stiffness = k;
  const double limit = (3.0 * std::numbers::pi / 16.0) * c.friction * a * c.f_n;
  if (std::abs(m) > limit) {
    const double trial = m;
    m = std::copysign(limit, trial);
    if constexpr (Energy) energy.dissipated_rolling += (before + m) * (trial - m) / (2.0 * k);
  } else if (p.damping_ratio > 0.0) {
    // With the rolling dashpot's inertia I_r (the grains' moments about the contact point):
    // for a sphere that is sqrt(3.5) times the critical damping of a twist about its centre
    // (docs/contact-law.md).
    viscous = -(2.0 * p.damping_ratio * std::sqrt(c.inertia * k)) * w_t;
    // Spring and dashpot together within the slip limit, as for rolling.
    if (std::abs(m + viscous) > limit) viscous = std::copysign(limit, m + viscous) - m;
    if constexpr (Energy) energy.dissipated_rolling -= 0.5 * viscous * w_t * c.dt;
  }
  if constexpr (Energy) energy.elastic_rolling += 0.5 * m * m / k;
  return m;
}

// Torque of the rolling resistance on body i (j receives its opposite). `viscous` receives
// the dashpot part of the torque (zero while the spring is at its limit), for the second half
// of its work (docs/integrator.md).
template <bool Energy>
[[gnu::always_inline]] inline Vec3 rolling_resistance(const RollingParameters& p, const RollingContact& c,
                                                      RollingSpring& s, ContactEnergy& energy,
                                                      Vec3& viscous) {
  const Vec3& n = c.normal;
  const double k_r = rolling_stiffness(c.k_n, p.friction, c.r_star);
  Vec3& m = s.torque;
  if (k_r > 0.0) carry_into_plane<Energy>(m, n, s.stiffness, k_r, energy.rolling_stiffness_change);
  const Vec3 before = m;  // the previous spring torque, in the present plane
  // Relative rolling: the part of omega_i - omega_j perpendicular to the normal (the normal
  // part is twisting, not resisted here).
  const Vec3 w_r = c.omega_rel - c.omega_rel.dot(n) * n;
  m -= k_r * c.dt * w_r;  // dM_r = -k_r dtheta_r (Ai et al. 2011)
  s.stiffness = k_r;
  const double limit = p.friction * c.r_star * c.f_n;  // full mobilisation (Ai et al. 2011)
  const double trial2 = m.squaredNorm();
  viscous = Vec3::Zero();
  if (trial2 > limit * limit) {
    const Vec3 trial = m;
    m *= limit / std::sqrt(trial2);  // plastic: the spring is rescaled, the dashpot is off (Ai et al., f = 0)
    if constexpr (Energy) energy.dissipated_rolling += slip_dissipation(before, trial, m, k_r);
  } else if (p.damping_ratio > 0.0) {
    // Dashpot C_r = eta_r C_r,crit, C_r,crit = 2 sqrt(I_r k_r) (Ai et al. 2011).
    viscous = -(2.0 * p.damping_ratio * std::sqrt(c.inertia * k_r)) * w_r;
    // The total torque stays within the plastic limit too: the dashpot is cut so that
    // |M_k + M_d| <= mu_r R* F_n. Without this, a spring just below a limit that grows with a
    // fluctuating F_n lets a dashpot torque far above the limit through while rolling fast.
    const Vec3 total = m + viscous;
    const double total2 = total.squaredNorm();
    if (total2 > limit * limit) viscous = total * (limit / std::sqrt(total2)) - m;
    // The v(k-1/2) half of its work, as the normal damping (contact_response.h).
    if constexpr (Energy) energy.dissipated_rolling -= 0.5 * viscous.dot(w_r) * c.dt;
  }
  // k_r = 0 (a rolling friction of 0, kept for twisting alone): no rolling spring, no energy.
  if constexpr (Energy) {
    if (k_r > 0.0) energy.elastic_rolling += 0.5 * m.squaredNorm() / k_r;
  }
  if (p.twisting_modulus > 0.0) {
    double twist_viscous = 0.0;
    const double twist = twisting_resistance<Energy>(p, c, s, energy, twist_viscous);
    viscous += twist_viscous * n;
    return m + viscous + twist * n;
  }
  return m + viscous;
}

// The rolling part of a contact law (law/contact_law.h), with the normal part's stiffness.
struct RollingSpringDashpot {
  static constexpr bool needs_history = true;
  static constexpr bool needs_rotation = true;
  template <bool Energy>
  [[gnu::always_inline]] static Vec3 torque(const RollingParameters& p, const RollingContact& c,
                                            RollingSpring& s, ContactEnergy& energy, Vec3& viscous) {
    return rolling_resistance<Energy>(p, c, s, energy, viscous);
  }
};

}  // namespace upgrain::dem
