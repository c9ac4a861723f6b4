#pragma once
// The normal dashpot of a contact law: c_n = 2 zeta sqrt(m* k_n) with the normal part's
// tangent stiffness (Yan and Regueiro eq. 21-22, docs/stress.md; Tsuji et al. 1992 for Hertz, Cundall and
// Strack 1979 for a linear spring), and a total normal force that never attracts.
#include "dem/contact/contact_parameters.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/normal_response.h"

namespace upgrain::dem {

struct ViscousDamping {
  static constexpr bool needs_history = false;
  static constexpr bool needs_rotation = false;

  // The normal force with the dashpot at approach speed v_n (> 0 approaching), clamped at 0.
  template <bool Energy>
  [[gnu::always_inline]] static double force(const ContactParameters& p, const NormalResponse& r, double v_n,
                                             ContactEnergy& energy) {
    double f_n = r.force + hertz::damping_coefficient(p.zeta, p.m_star, r.stiffness) * v_n;
    f_n = f_n > 0.0 ? f_n : 0.0;  // the normal force is never attractive
    // A force evaluated at step k does work over the two half kicks around k, i.e. with the
    // mean of v(k-1/2) and v(k+1/2) (docs/integrator.md). This is the v(k-1/2) half; the
    // Simulation adds the other half after its next first kick.
    if constexpr (Energy) energy.dissipated_damping += 0.5 * (f_n - r.force) * v_n * p.dt;
    return f_n;
  }
};

}  // namespace upgrain::dem
