#pragma once
// The values of one contact evaluation the force loop fills per pair or wall entry, the pair
// and wall constants of a law, and the energy accounts a contact books into. Plain data shared
// by every part of every contact law (dem/contact/law/).
#include <cmath>

#include "dem/core/types.h"

namespace upgrain::dem {

// What the parts of a law read of one contact besides its geometry: the law's own constants
// (its normal part's `Constants`) come beside it, from the law (contact_response.h).
struct ContactParameters {
  double r_star = 0.0;    // effective radius (m)
  double m_star = 0.0;    // effective mass (kg)
  double friction = 0.0;  // Coulomb coefficient
  double zeta = 0.0;      // damping ratio
  double dt = 0.0;        // time step (s)
};

// A law's constants between two grains and between a grain and a wall (each law says how the
// two follow from the scene: dem/contact/law/).
template <class Constants>
struct PairAndWall {
  Constants pair;
  Constants wall;
};

struct ContactEnergy {
  double elastic_normal = 0.0;
  double elastic_tangential = 0.0;
  double dissipated_damping = 0.0;
  double dissipated_friction = 0.0;
  // Change of the stored tangential energy |F_t|^2 / (2 k_t) caused by k_t following the
  // overlap while F_t is held: the incremental Mindlin spring is not a potential, and
  // this term is what it creates (> 0) or destroys (< 0). Accounted separately so the
  // balance error measures the integration (docs/contact-law.md, energy).
  double tangential_stiffness_change = 0.0;
  // Rolling resistance (contact/rolling_resistance.h): the spring's energy |M_r|^2 / (2 k_r),
  // its plastic and viscous dissipation (increment), and the energy its stiffness change
  // creates, as for the tangential spring.
  double elastic_rolling = 0.0;
  double dissipated_rolling = 0.0;
  double rolling_stiffness_change = 0.0;
  // Work a moving wall did on the grain through this contact in the step (F . v_wall dt): energy
  // put into the system, with a minus sign in the balance.
  double wall_work = 0.0;
};

// A particle's share of the contact energies (the deterministic summation books each contact on
// the particle it is first in): the elastic energies of one evaluation, and the dissipation
// since the last neighbour-list rebuild (dem/engine/simulation.h).
struct ElasticEnergy {
  double normal = 0.0, tangential = 0.0, rolling = 0.0;
};
struct DissipatedEnergy {
  double damping = 0.0, friction = 0.0, stiffness_change = 0.0, rolling = 0.0, rolling_stiffness_change = 0.0;
  double wall_work = 0.0;  // work done by moving walls (energy put in)
};
inline void book(const ContactEnergy& ce, ElasticEnergy& e) {
  e.normal += ce.elastic_normal;
  e.tangential += ce.elastic_tangential;
  e.rolling += ce.elastic_rolling;
}
inline void book(const ContactEnergy& ce, DissipatedEnergy& d) {
  d.damping += ce.dissipated_damping;
  d.friction += ce.dissipated_friction;
  d.stiffness_change += ce.tangential_stiffness_change;
  d.rolling += ce.dissipated_rolling;
  d.rolling_stiffness_change += ce.rolling_stiffness_change;
}
// The same with a moving wall's work: for wall contacts and for a rank's running sums only,
// so the pair loop does not carry a channel that is zero there.
inline void book_with_wall_work(const ContactEnergy& ce, DissipatedEnergy& d) {
  book(ce, d);
  d.wall_work += ce.wall_work;
}

// The energy a slip of an incremental spring (stiffness k) dissipates in one step: from
// `before` (the previous value, carried into the present plane) the increment gave `trial`,
// which the slip cut back to `after`. Velocity Verlet applies each force for half a step
// before and half a step after its evaluation, so the spring's work over the step's
// displacement (before - trial)/k is the trapezoid -(before + after).(before - trial)/(2k);
// with the stored energy's change (|after|^2 - |before|^2)/(2k) it leaves
// (before + after).(trial - after)/(2k) dissipated. Booking |after| (|trial| - |after|)/k (the
// value after the slip alone) instead misses (after - before).(trial - after)/(2k) whenever the
// limit changes while slipping: a balance error of first order in the time step
// (docs/hard-cases.md, "Energy accounting of friction").
[[gnu::always_inline]] inline double slip_dissipation(const Vec3& before, const Vec3& trial,
                                                      const Vec3& after, double k) {
  return (before + after).dot(trial - after) / (2.0 * k);
}

// An incremental spring's stored vector (a tangential force, a rolling torque) carried into
// the current contact plane of normal n with its magnitude kept, and the energy that the
// stiffness's change from `old_stiffness` to `stiffness` creates in it, |s|^2/2 (1/k - 1/k_old),
// added to `stiffness_change` (docs/contact-law.md, energy). A new spring (old stiffness 0)
// creates none.
template <bool Energy>
[[gnu::always_inline]] inline void carry_into_plane(Vec3& s, const Vec3& n, double old_stiffness,
                                                    double stiffness, double& stiffness_change) {
  const double old_norm2 = s.squaredNorm();
  if (old_norm2 > 0.0) {
    s -= s.dot(n) * n;
    const double new_norm2 = s.squaredNorm();
    if (new_norm2 > 0.0) s *= std::sqrt(old_norm2 / new_norm2);
    if constexpr (Energy) {
      if (old_stiffness > 0.0) stiffness_change += 0.5 * old_norm2 * (1.0 / stiffness - 1.0 / old_stiffness);
    }
  }
}

}  // namespace upgrain::dem
