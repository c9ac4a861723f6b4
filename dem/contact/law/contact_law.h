#pragma once
// A contact law composed of parts, each a small value type with static flags (does it need
// history? rotation?), as LAMMPS's granular sub-models (normal, damping, tangential,
// rolling) are: the force loop (dem/engine/force_loop_body.h) is compiled once per law,
// shape pair class and effect set, and calls each part through the law. The normal part
// is what distinguishes one law from another (law/hertz.h, law/hooke.h); it gives the
// stiffness the dashpot and the tangential and rolling springs use. The table of laws a
// scene can choose is dem/contact/contact_laws.h. docs/contact-law.md.
#include "dem/contact/law/coulomb_spring.h"
#include "dem/contact/law/viscous_damping.h"
#include "dem/contact/rolling_resistance.h"

namespace upgrain::dem {

template <class NormalPart, class DampingPart = ViscousDamping, class TangentialPart = CoulombSpring,
          class RollingPart = RollingSpringDashpot>
struct ContactLaw {
  using Normal = NormalPart;
  using Damping = DampingPart;
  using Tangential = TangentialPart;
  using Rolling = RollingPart;
  static constexpr const char* name = Normal::name;
};

}  // namespace upgrain::dem
