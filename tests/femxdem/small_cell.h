#pragma once
// The DEM cell the FEM x DEM tests use (tests/femxdem/, tests/fem/femxdem_element_test.cc):
// 60 Hertz-Mindlin spheres prepared at 100 kPa.
#include "coupling/femxdem/rve_options.h"
#include "dem/scene/scene_config.h"

namespace upgrain::coupling {

// Spheres of 1 mm with a 20 % spread, soft enough for a coarse step: E = 1e8 Pa (mean overlaps of
// about 4 % of the radius at 100 kPa, measured in rve_cell_test.cc), dt a fifth of the Rayleigh
// time.
inline dem::SceneConfig sphere_scene() {
  dem::SceneConfig s;
  s.particles.radius = 1e-3;
  s.particles.gradation = {{0.8e-3, 0.0}, {1.2e-3, 1.0}};
  s.particles.material = {2650.0, 1e8, 0.25};
  s.friction = 0.5;
  s.damping_ratio = 0.5;
  s.time_step = 4e-6;
  return s;
}

inline RveOptions small_cell() {
  RveOptions o;
  o.grains = 60;
  return o;
}

}  // namespace upgrain::coupling
