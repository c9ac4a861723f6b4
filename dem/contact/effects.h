#pragma once
// The physical effects a scene opts into. The force loop is a template on the subset that
// matters for contact forces, instantiated once per combination and chosen once per run
// (contact/force_kernel.h), so a frictionless scene carries no tangential history and no
// rotation work (STYLE.md section 1).

namespace upgrain::dem {

struct EffectSet {
  bool gravity = true;
  bool friction = true;         // tangential Mindlin spring + Coulomb between particles
  bool damping = true;          // normal viscous damping, brief eq. (21)
  bool wall_friction = true;    // tangential Mindlin spring + Coulomb at walls
  bool rotation = true;         // integrate angular velocity from contact torques
  bool energy_tracking = true;  // accumulate dissipation and elastic energy per contact

  // Tangential history is only carried when some tangential force exists.
  [[nodiscard]] bool needs_history() const { return friction || wall_friction; }
};

template <bool Friction, bool Damping, bool WallFriction, bool Rotation, bool Energy>
struct Effects {
  static constexpr bool friction = Friction;
  static constexpr bool damping = Damping;
  static constexpr bool wall_friction = WallFriction;
  // Spheres only feel torque from tangential forces: no friction, no rotation work.
  static constexpr bool rotation = Rotation && (Friction || WallFriction);
  static constexpr bool energy = Energy;
};

}  // namespace upgrain::dem
