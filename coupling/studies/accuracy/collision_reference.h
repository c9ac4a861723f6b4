#pragma once
// The exact reference of the time-step knob (docs/accuracy.md): a head-on collision of two
// equal grains of the scene's material, at the scene's impact speed, without damping,
// friction or gravity, whose duration and restitution are known in closed form: Hertz
// (Johnson 1985, eq. 11.24) for the Hertz-Mindlin law, pi sqrt(m*/k_n) for the linear spring,
// and a restitution of 1 for both. The engine runs it with the step to be judged.
#include "dem/scene/scene_config.h"

namespace upgrain::coupling {

struct CollisionError {
  double duration = 0.0;     // relative error of the contact duration
  double restitution = 0.0;  // |e - 1|
  double steps_in_contact = 0.0;
};

// Spheres of radius `radius`; the contact's start and end are interpolated within their steps
// from the overlap, so the duration's error shows the integrator's order, not the step's size.
CollisionError collision_error(const dem::SceneConfig& scene, double radius, double speed, double dt);

}  // namespace upgrain::coupling
