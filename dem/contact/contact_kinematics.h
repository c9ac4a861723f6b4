#pragma once
// One contact as the contact law sees it: its geometry (from the shape pair's geometry,
// dem/contact/geometry/pair_geometries.h) and the motion of both bodies.
#include "dem/core/types.h"

namespace upgrain::dem {

struct ContactKinematics {
  Vec3 normal;     // unit normal, from body i towards body j
  double overlap;  // delta > 0
  Vec3 lever_i;    // from centroid i to the contact point (spheres: (r_i - delta/2) n)
  Vec3 lever_j;    // from centroid j to the contact point (spheres: -(r_j - delta/2) n)
  Vec3 v_i, v_j, omega_i, omega_j;
};

}  // namespace upgrain::dem
