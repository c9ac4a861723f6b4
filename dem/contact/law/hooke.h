#pragma once
// The linear spring-dashpot contact law (Cundall and Strack 1979, Geotechnique 29:47; LAMMPS
// `hooke` with `tangential linear_history`): F_n = k_n delta with a constant k_n, a constant
// tangential spring k_t, and the normal dashpot c_n = 2 zeta sqrt(m* k_n) and Coulomb cap of
// contact_law.h. With the dashpot constant, a collision is a damped harmonic oscillation:
// omega_0 = sqrt(k_n / m*), omega_d = omega_0 sqrt(1 - zeta^2), duration pi / omega_d and
// restitution exp(-zeta pi / sqrt(1 - zeta^2)) while the force stays repulsive; with the
// no-attraction clamp the contact ends earlier, where the force first reaches zero
// (docs/contact-law.md, "The linear spring-dashpot").
#include <array>
#include <cmath>
#include <numbers>
#include <span>

#include "dem/contact/contact_parameters.h"
#include "dem/contact/law/contact_law.h"
#include "dem/contact/law/law_parameter.h"
#include "dem/contact/law/normal_response.h"
#include "dem/contact/law/time_scales.h"
#include "dem/core/material.h"

namespace upgrain::dem {

struct HookeNormal {
  static constexpr const char* name = "hooke";
  static constexpr const char* description =
      "linear spring-dashpot (Cundall and Strack 1979) with 'normal stiffness' and 'tangential stiffness'.";
  static constexpr bool needs_history = false;
  static constexpr bool needs_rotation = false;
  static constexpr std::array<LawParameter, 2> parameters{{
      {"normal stiffness", "1e5", 1e-6, 1e15, "N/m",
       "k_n of the linear spring-dashpot (Contact/law = hooke): F_n = k_n delta, particle-particle and "
       "particle-wall."},
      {"tangential stiffness", "0", 0.0, 1e15, "N/m",
       "k_t of the tangential spring of the linear law (Contact/law = hooke); 0 = 2/7 k_n (Silbert et al. "
       "2001, LAMMPS's default)."},
  }};

  // Its constants, particle-particle and particle-wall alike.
  struct Constants {
    double k_n = 0.0;  // normal spring constant (N/m)
    double k_t = 0.0;  // tangential spring constant (N/m)
  };
  static PairAndWall<Constants> constants(const Material&, std::span<const NamedValue> values) {
    Constants c;
    c.k_n = law_parameter(values, parameters[0]);
    const double k_t = law_parameter(values, parameters[1]);
    c.k_t = k_t > 0.0 ? k_t : 2.0 / 7.0 * c.k_n;
    return {c, c};
  }

  [[gnu::always_inline]] static NormalResponse response(const Constants& c, const ContactParameters&,
                                                        double delta) {
    return {c.k_n * delta, c.k_n, c.k_t};
  }
  // The spring's energy k_n delta^2 / 2.
  [[gnu::always_inline]] static double energy(const NormalResponse& r, double delta) {
    return 0.5 * r.force * delta;
  }

  // An undamped collision lasts half a period of the oscillator, pi / omega_0 = pi sqrt(m* / k_n),
  // at any speed.
  static double collision_duration(const Constants& c, double, double m_star, double) {
    return std::numbers::pi * std::sqrt(m_star / c.k_n);
  }

  // The lightest pair (m* = m / 2) has the shortest collision. dt <= (Hertz fraction) of it:
  // the one contact-duration fraction serves every law (docs/contact-law.md, time step). No
  // Rayleigh limit: k_n is not the grains' elasticity.
  static LawTimeLimit time_limit(const PairAndWall<Constants>& c, const SceneTimeScales& s, double,
                                 double duration_fraction) {
    LawTimeLimit t;
    t.contact_time = collision_duration(c.pair, 0.0, 0.5 * s.lightest, 0.0);
    t.safe_step = duration_fraction * t.contact_time;
    t.limiting = "Hooke";
    return t;
  }
};

using Hooke = ContactLaw<HookeNormal>;

}  // namespace upgrain::dem
