#pragma once
// The Hertz-Mindlin contact law (Yan and Regueiro's law; docs/contact-law.md, docs/stress.md): Hertz's normal
// force of two elastic spheres and Mindlin's no-slip tangential stiffness, with the normal
// dashpot, the Coulomb-capped incremental tangential spring and the rolling spring-dashpot
// of contact_law.h. Its time-step rule: the Rayleigh time and the Hertz contact duration.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>

#include "dem/contact/contact_parameters.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/contact_law.h"
#include "dem/contact/law/law_parameter.h"
#include "dem/contact/law/normal_response.h"
#include "dem/contact/law/time_scales.h"
#include "dem/core/material.h"

namespace upgrain::dem {

struct HertzNormal {
  static constexpr const char* name = "hertz-mindlin";
  static constexpr const char* description =
      "Hertz normal force and Mindlin tangential stiffness from the grains' E and nu (Yan and Regueiro's "
      "law).";
  static constexpr bool needs_history = false;
  static constexpr bool needs_rotation = false;
  // Its constants: the effective moduli of the contact, from the grains' E and nu (Particles
  // section); no parameters of its own.
  struct Constants {
    double e_star = 0.0;  // 1/E* = 2 (1 - nu^2) / E (Johnson 1985, eq. 4.22), Pa
    double g_star = 0.0;  // 1/G* = 2 (2 - nu) / G (Mindlin 1949; Di Renzo and Di Maio 2004, eq. 9), Pa
  };
  static constexpr std::array<LawParameter, 0> parameters{};
  // A rigid, frictional wall is a plane of the grains' own material: the same E and nu (the
  // convention of LIGGGHTS' wall/gran; docs/contact-law.md).
  static PairAndWall<Constants> constants(const Material& m, std::span<const NamedValue>) {
    const Constants c{effective_youngs_modulus(m, m), effective_shear_modulus(m, m)};
    return {c, c};
  }

  // F = 4/3 E* a delta, k_n = 2 E* a, k_t = 8 G* a with the contact radius a = sqrt(R* delta)
  // (hertz_mindlin.h; Johnson 1985, eq. 4.23; Mindlin 1949).
  [[gnu::always_inline]] static NormalResponse response(const Constants& c, const ContactParameters& p,
                                                        double delta) {
    const double a = hertz::contact_radius(p.r_star, delta);
    return {hertz::normal_force_at(c.e_star, a, delta), hertz::normal_stiffness_at(c.e_star, a),
            hertz::tangential_stiffness_at(c.g_star, a)};
  }
  // 8/15 E* sqrt(R*) delta^(5/2) = 2/5 F delta.
  [[gnu::always_inline]] static double energy(const NormalResponse& r, double delta) {
    return 0.4 * r.force * delta;
  }

  // The duration of an undamped head-on collision at approach speed v: 2.87 (m*^2 / (R* E*^2
  // v))^(1/5) (Johnson 1985, eq. 11.24; hertz_mindlin.h).
  static double collision_duration(const Constants& c, double r_star, double m_star, double speed) {
    return hertz::contact_duration(c.e_star, r_star, m_star, speed);
  }

  // dt <= Rayleigh fraction T_R of the thinnest grain and <= Hertz fraction t_H of the
  // stiffest, lightest contact at the impact speed (docs/contact-law.md, time step).
  static LawTimeLimit time_limit(const PairAndWall<Constants>& c, const SceneTimeScales& s,
                                 double rayleigh_fraction, double duration_fraction) {
    const Material& m = s.material;
    LawTimeLimit t;
    // Rayleigh time T_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766) (Li et al. 2005; Thornton 2015).
    t.rayleigh_time = std::numbers::pi * s.thinnest * s.r_min * std::sqrt(m.density / m.shear_modulus()) /
                      (0.1631 * m.poisson_ratio + 0.8766);
    const double t_pp =
        collision_duration(c.pair, 0.5 * s.flattest * s.r_min, 0.5 * s.lightest, s.impact_speed);
    const double t_pw = collision_duration(c.wall, s.flattest * s.r_min, s.lightest, s.impact_speed);
    t.contact_time = std::min(t_pp, t_pw);
    const double by_rayleigh = rayleigh_fraction * t.rayleigh_time;
    const double by_contact = duration_fraction * t.contact_time;
    t.safe_step = std::min(by_rayleigh, by_contact);
    t.limiting = by_rayleigh <= by_contact ? "Rayleigh" : "Hertz";
    return t;
  }
};

using HertzMindlin = ContactLaw<HertzNormal>;

}  // namespace upgrain::dem
