#pragma once
// The tangential part of a contact law: an incremental spring dF_t = -k_t du_t capped by
// Coulomb's |F_t| <= mu F_n, carried per contact in the history store and turned into the
// current tangent plane at each step (Mindlin and Deresiewicz 1953 as used by Di Renzo and
// Di Maio 2004; LAMMPS `tangential mindlin` / `linear_history`). The stiffness k_t is the
// normal part's (NormalResponse::tangential_stiffness).
#include <cmath>

#include "dem/contact/contact_parameters.h"
#include "dem/core/contact_history.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// One contact as the tangential part sees it.
struct TangentialMotion {
  const Vec3& normal;  // unit contact normal, from i towards j
  const Vec3& v_t;     // tangential velocity of i relative to j at the contact point
  double k_t;          // tangential stiffness (NormalResponse::tangential_stiffness)
  double f_n;          // normal force after the dashpot: the scale of the Coulomb cap
};

struct CoulombSpring {
  static constexpr bool needs_history = true;
  static constexpr bool needs_rotation = true;  // its force is off the centres: a torque

  // The tangential force on i for the contact's tangential motion, with its normal force as
  // the Coulomb cap; updates the stored spring.
  template <bool Energy>
  [[gnu::always_inline]] static Vec3 force(const ContactParameters& p, const TangentialMotion& m,
                                           TangentialSpring& spring, ContactEnergy& energy) {
    const Vec3& n = m.normal;
    const Vec3& v_t = m.v_t;
    const double k_t = m.k_t, f_n = m.f_n;
    Vec3& f_t = spring.force;
    carry_into_plane<Energy>(f_t, n, spring.stiffness, k_t, energy.tangential_stiffness_change);
    const Vec3 before = f_t;  // the previous force, in the present plane
    f_t -= k_t * p.dt * v_t;  // incremental: dF_t = -k_t du_t
    spring.stiffness = k_t;
    const double limit = p.friction * f_n;
    const double trial2 = f_t.squaredNorm();
    if (trial2 > limit * limit) {
      const Vec3 trial = f_t;
      f_t *= limit / std::sqrt(trial2);  // Coulomb: the stored spring is rescaled on slip
      if constexpr (Energy) energy.dissipated_friction += slip_dissipation(before, trial, f_t, k_t);
    }
    if constexpr (Energy) energy.elastic_tangential += 0.5 * f_t.squaredNorm() / k_t;
    return f_t;
  }
};

}  // namespace upgrain::dem
