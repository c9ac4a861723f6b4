#pragma once
// Force of one contact, given its geometry (unit normal from i towards j, overlap, lever
// arms) and the kinematics of both bodies, by a contact law composed of parts
// (dem/contact/law/contact_law.h): the law's normal force, the normal dashpot and the
// Coulomb-capped tangential spring. Templated on the effect set: what a scene switches off
// is not computed. Equations and sign conventions: docs/contact-law.md.
#include <cmath>

#include "dem/contact/contact_kinematics.h"
#include "dem/contact/contact_parameters.h"
#include "dem/contact/law/hertz.h"
#include "dem/core/contact_history.h"
#include "dem/core/types.h"

namespace upgrain::dem {

struct ContactForce {
  Vec3 on_i;         // force on body i; body j receives -on_i
  double normal;     // magnitude of the (repulsive) normal force, >= 0
  double damping;    // its viscous part (normal minus elastic), along -normal on i
  double stiffness;  // the law's tangent normal stiffness k_n (for the rolling spring)
};

// c: the law's constants for this kind of contact (pair or wall, PairAndWall). spring: the
// tangential force of this contact on i, carried from the previous step (incremental spring).
// Updated in place.
// Always inlined into the force loop: as a call, the kinematics are copied through memory
// per contact (measured with callgrind: about a fifth of the loop's instructions).
template <bool Tangential, bool Damping, bool Rotation, bool Energy, class Law = HertzMindlin>
[[gnu::always_inline]] inline ContactForce contact_response(const typename Law::Normal::Constants& c,
                                                            const ContactParameters& p,
                                                            const ContactKinematics& k,
                                                            TangentialSpring& spring, ContactEnergy& energy) {
  using Normal = typename Law::Normal;
  const Vec3& n = k.normal;
  const double delta = k.overlap;
  const NormalResponse r = Normal::response(c, p, delta);

  // Relative velocity of i with respect to j at the contact point.
  Vec3 v_rel = k.v_i - k.v_j;
  if constexpr (Rotation) {
    v_rel += k.omega_i.cross(k.lever_i) - k.omega_j.cross(k.lever_j);
  }
  const double v_n = v_rel.dot(n);  // > 0 while approaching

  double f_n = r.force;
  if constexpr (Damping) f_n = Law::Damping::template force<Energy>(p, r, v_n, energy);
  if constexpr (Energy) energy.elastic_normal += Normal::energy(r, delta);

  ContactForce out;
  out.normal = f_n;
  out.damping = f_n - r.force;
  out.stiffness = r.stiffness;
  out.on_i = -f_n * n;
  if constexpr (Tangential) {
    const Vec3 v_t = v_rel - v_n * n;
    out.on_i +=
        Law::Tangential::template force<Energy>(p, {n, v_t, r.tangential_stiffness, f_n}, spring, energy);
  }
  return out;
}

}  // namespace upgrain::dem
