#pragma once
// Small hand-built scenes for physics tests.
#include "dem/scene/scene_config.h"

namespace upgrain::test {

// A soft, paper-like material so that tests need few steps: r = 5 mm, rho = 2650,
// E = 1e8 Pa, nu = 0.25. Every effect off; tests switch on what they check.
inline dem::SceneConfig bare_scene(double dt) {
  dem::SceneConfig s;
  s.particles.material = {2650.0, 1e8, 0.25};
  s.effects = {false, false, false, false, false, true};
  s.time_step = dt;
  s.friction = 0.5;
  s.damping_ratio = 0.0;
  s.neighbor_skin = 0.1;
  return s;
}

}  // namespace upgrain::test
