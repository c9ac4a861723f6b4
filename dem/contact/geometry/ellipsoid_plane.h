#pragma once
// An ellipsoid against a plane wall, closed form: its lowest point along -normal
// (docs/ellipsoid-contact.md), with the elliptic Hertz radius held from first touch.
#include <cstddef>

#include "dem/contact/contact_kinematics.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/grain_poses.h"
#include "dem/core/particle_store.h"
#include "dem/core/plane_wall.h"

namespace upgrain::dem {

// The ellipsoid's row of the wall-geometry table (pair_geometries.h).
struct EllipsoidPlane {
  static constexpr bool closed_form = false;
  static constexpr const char* name = "ellipsoid-plane, support point";

  // Grain i (posed in `poses`) against `wall`. Returns false when apart (then r_held = 0).
  // Sets the overlap and lever of `kin` (the caller sets kin.normal = -wall.normal) and the
  // Hertz radius, held from first touch in r_held, as for pairs.
  [[gnu::always_inline]] static bool touching(const GrainPoses& poses, std::size_t i, const PlaneWall& wall,
                                              double& r_held, ContactKinematics& kin) {
    const ContactGeometry g = posed_plane_contact(poses[i], Plane{wall.point, wall.normal}, r_held == 0.0);
    if (!g.touching) {
      r_held = 0.0;
      return false;
    }
    kin.overlap = g.depth;
    kin.lever_i = g.lever1;
    if (r_held == 0.0) r_held = gaussian_curvature_radius(g);
    return true;
  }

  // How far grain i of `p` reaches behind `wall`, outside the force loop (wall_depth()): its
  // support along the wall's normal, sqrt(m^T M m) (docs/ellipsoid-contact.md), less its
  // centre's distance.
  static double depth(const ParticleStore& p, std::size_t i, const PlaneWall& wall) {
    return (p.orientation[i].conjugate() * wall.normal).cwiseProduct(p.semi_axes[i]).norm() -
           (p.x[i] - wall.point).dot(wall.normal);
  }
};

}  // namespace upgrain::dem
