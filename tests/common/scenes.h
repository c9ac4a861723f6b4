#pragma once
// Small hand-built scenes for physics tests.
#include "dem/core/particle_store.h"
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

// 27 spheres of radius r on a slightly sheared 3 x 3 x 3 lattice (pitch 12 mm, from 8 mm), thrown
// down at 0.2 m/s with a spread of sideways velocities, each column of x spinning about z at
// `spin` times (ix - 1): the energy-balance scene of the rolling and twisting resistance tests.
inline dem::ParticleStore box_of_27_spheres(double r, double spin = 0.0) {
  dem::ParticleStore p;
  dem::GlobalId id = 0;
  for (int ix = 0; ix < 3; ++ix)
    for (int iy = 0; iy < 3; ++iy)
      for (int iz = 0; iz < 3; ++iz) {
        const dem::Vec3 x(0.008 + 0.012 * ix + 0.001 * iz, 0.008 + 0.012 * iy + 0.0007 * ix,
                          0.008 + 0.012 * iz);
        p.add_sphere(id, r, 2650, x, dem::Vec3(0.1 * (iy - 1), 0.05 * (iz - 1), -0.2),
                     dem::Vec3(0, 0, spin * (ix - 1)));
        ++id;
      }
  return p;
}

}  // namespace upgrain::test
