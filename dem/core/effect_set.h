#pragma once
// The physical effects a run simulates, as plain data: derived from the scene's parameters
// (dem/scene/effect_choice.h) and turned into the force loop's template arguments once per
// run (dem/contact/effects.h).

namespace upgrain::dem {

struct EffectSet {
  bool gravity = true;
  bool friction = true;         // tangential Mindlin spring + Coulomb between particles
  bool damping = true;          // normal viscous damping, Yan and Regueiro eq. (21)
  bool wall_friction = true;    // tangential Mindlin spring + Coulomb at walls
  bool rotation = true;         // integrate angular velocity from contact torques
  bool energy_tracking = true;  // accumulate dissipation and elastic energy per contact
  // Rolling resistance (elastic-plastic spring-dashpot, contact/rolling_resistance.h) at
  // every contact. Off by default: not part of Yan and Regueiro's law (docs/stress.md). Needs rotation.
  bool rolling_resistance = false;
  // Twisting resistance (Hertz–Mindlin torsion, contact/rolling_resistance.h): a part of the
  // rolling resistance's springs, so only with it. Off by default.
  bool twisting_resistance = false;

  // Tangential history is only carried when some tangential force exists.
  [[nodiscard]] bool needs_history() const { return friction || wall_friction; }
  // Whether the grains' rotation is integrated: spheres turn only under tangential forces
  // and rolling resistance, ellipsoids under normal forces as well (`shapes`).
  [[nodiscard]] bool integrates_rotation(bool shapes) const {
    return rotation && (friction || wall_friction || rolling_resistance || shapes);
  }
};

}  // namespace upgrain::dem
