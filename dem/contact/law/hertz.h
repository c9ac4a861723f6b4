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
      "Hertz normal force and Mindlin tangential stiffness from the grains' E and nu (the paper's law).";
  static constexpr bool needs_history = false;
  static constexpr bool needs_rotation = false;
  // Its coefficients are the grains' E and nu (Particles section): none of its own.
  static constexpr std::array<LawParameter, 0> parameters{};
  static void constants(std::span<const NamedValue>, ContactMaterial&) {}

  // F = 4/3 E* a delta, k_n = 2 E* a, k_t = 8 G* a with the contact radius a = sqrt(R* delta)
  // (hertz_mindlin.h; Johnson 1985, eq. 4.23; Mindlin 1949).
  [[gnu::always_inline]] static NormalResponse response(const ContactParameters& p, double delta) {
    const double a = hertz::contact_radius(p.r_star, delta);
    return {hertz::normal_force_at(p.e_star, a, delta), hertz::normal_stiffness_at(p.e_star, a),
            hertz::tangential_stiffness_at(p.g_star, a)};
  }
  // 8/15 E* sqrt(R*) delta^(5/2) = 2/5 F delta.
  [[gnu::always_inline]] static double energy(const NormalResponse& r, double delta) {
    return 0.4 * r.force * delta;
  }

  // dt <= Rayleigh fraction T_R of the thinnest grain and <= Hertz fraction t_H of the
  // stiffest, lightest contact at the impact speed (docs/contact-law.md, time step).
  static LawTimeLimit time_limit(const SceneTimeScales& s, double rayleigh_fraction,
                                 double duration_fraction) {
    const Material& m = s.material;
    LawTimeLimit t;
    // Rayleigh time T_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766) (Li et al. 2005; Thornton 2015).
    t.rayleigh_time = std::numbers::pi * s.thinnest * s.r_min * std::sqrt(m.density / m.shear_modulus()) /
                      (0.1631 * m.poisson_ratio + 0.8766);
    const double e_star = effective_youngs_modulus(m, m);  // particle-wall: the same material
    const double t_pp =
        hertz::contact_duration(e_star, 0.5 * s.flattest * s.r_min, 0.5 * s.lightest, s.impact_speed);
    const double t_pw = hertz::contact_duration(e_star, s.flattest * s.r_min, s.lightest, s.impact_speed);
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
