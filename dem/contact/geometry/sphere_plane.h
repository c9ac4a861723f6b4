#pragma once
// Sphere against a plane wall in closed form: overlap r - gap, normal along the wall's normal,
// the contact point on the plane at arm gap from the centre, and R* = r (the wall is flat).
#include <cstddef>

#include "dem/contact/contact_kinematics.h"
#include "dem/core/particle_store.h"
#include "dem/core/plane_wall.h"

namespace upgrain::dem {

// Sets the overlap and lever of `kin` (the caller sets kin.normal = -wall normal) for a sphere
// of radius r at distance gap < r from the plane; returns the lever length gap, along the
// normal, for the torque gap n x F.
[[gnu::always_inline]] inline double sphere_plane_kinematics(double gap, double r, ContactKinematics& kin) {
  kin.overlap = r - gap;
  kin.lever_i = gap * kin.normal;
  return gap;
}

// The sphere's row of the wall-geometry table (pair_geometries.h): closed form, evaluated in
// the wall loop itself.
struct SpherePlane {
  static constexpr bool closed_form = true;
  static constexpr const char* name = "sphere-plane, closed form";

  // How far grain i of `p` reaches behind `wall`, outside the force loop (wall_depth()).
  static double depth(const ParticleStore& p, std::size_t i, const PlaneWall& wall) {
    return p.radius[i] - (p.x[i] - wall.point).dot(wall.normal);
  }
};

}  // namespace upgrain::dem
