#pragma once
// The effect set as types: the force loop is a template on the subset of EffectSet
// (dem/core/effect_set.h) that matters for contact forces, instantiated once per
// combination and chosen once per run (dem/engine/force_loop.h), so a frictionless scene
// carries no tangential history and no rotation work (docs/architecture.md).
#include "dem/core/effect_set.h"

namespace upgrain::dem {

template <bool Friction, bool Damping, bool WallFriction, bool Rotation, bool Energy, bool Rolling = false>
struct Effects {
  static constexpr bool friction = Friction;
  static constexpr bool damping = Damping;
  static constexpr bool wall_friction = WallFriction;
  // Spheres only feel torque from tangential forces and rolling resistance: without them,
  // no rotation work.
  static constexpr bool rotation = Rotation && (Friction || WallFriction || Rolling);
  // Non-spherical grains turn under normal forces too (dem/engine/force_loop_body.h).
  static constexpr bool rotation_requested = Rotation;
  static constexpr bool energy = Energy;
  static constexpr bool rolling = Rolling && Rotation;
};

// Turns the run-time effect set into the matching Effects<...> type, once per run: calls
// make.template operator()<Effects<...>>() and returns its result. Every force loop that
// is a template on Effects picks its instantiation through this one ladder.
template <class Make>
auto with_effects(const EffectSet& e, Make make) {
  auto energy = [&]<bool F, bool D, bool W, bool R>() {
    return e.energy_tracking ? make.template operator()<Effects<F, D, W, R, true>>()
                             : make.template operator()<Effects<F, D, W, R, false>>();
  };
  auto rotation = [&]<bool F, bool D, bool W>() {
    return e.rotation ? energy.template operator()<F, D, W, true>()
                      : energy.template operator()<F, D, W, false>();
  };
  auto wall = [&]<bool F, bool D>() {
    return e.wall_friction ? rotation.template operator()<F, D, true>()
                           : rotation.template operator()<F, D, false>();
  };
  auto damping = [&]<bool F>() {
    return e.damping ? wall.template operator()<F, true>() : wall.template operator()<F, false>();
  };
  return e.friction ? damping.template operator()<true>() : damping.template operator()<false>();
}

// The same ladder for scenes with rolling resistance: rotation is on (the engine refuses
// rolling resistance without it), so only friction, damping, wall friction and energy
// tracking vary. Scenes without it keep the instantiations of with_effects.
template <class Make>
auto with_rolling_effects(const EffectSet& e, Make make) {
  auto energy = [&]<bool F, bool D, bool W>() {
    return e.energy_tracking ? make.template operator()<Effects<F, D, W, true, true, true>>()
                             : make.template operator()<Effects<F, D, W, true, false, true>>();
  };
  auto wall = [&]<bool F, bool D>() {
    return e.wall_friction ? energy.template operator()<F, D, true>()
                           : energy.template operator()<F, D, false>();
  };
  auto damping = [&]<bool F>() {
    return e.damping ? wall.template operator()<F, true>() : wall.template operator()<F, false>();
  };
  return e.friction ? damping.template operator()<true>() : damping.template operator()<false>();
}

}  // namespace upgrain::dem
