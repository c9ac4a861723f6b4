#pragma once
// The geometry of ellipsoid contacts as the force loops use it, shared by the serial loop
// (force_kernel.cc) and the deterministic parallel loop (parallel/deterministic_forces.cc),
// so that both evaluate a contact with the same operations (docs/ellipsoids.md).
#include <optional>
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/contact/contact_response.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/core/particle_store.h"

namespace upgrain::dem {

// Geometry of a pair with at least one ellipsoid (docs/ellipsoids.md): bounding spheres
// (already tested by the caller), then on one pair frame a conservative separation proof and
// the support-function solver warm-started from the pair's previous normal. Returns false
// when apart. `memory` keeps the last normal of a near pair (the next step's warm start) and
// the Hertz radius of a touching one; its normal points from i to j.
inline bool shaped_pair_geometry(const ParticleStore& p, const std::vector<PosedEllipsoid>& posed,
                                 std::size_t i, std::size_t j, ShapedContactMemory& memory,
                                 ContactSolverStats& stats, ContactKinematics& kin, double& r_star) {
  const bool first_touch = memory.r_star == 0.0;  // curvatures are needed only then
  ContactGeometry g;
  if (!posed_contact(posed[i], posed[j], stats,
                     memory.normal != Vec3::Zero() ? std::optional<Vec3>(memory.normal) : std::nullopt,
                     first_touch, g)) {
    // Proven apart: the direction of the proof is the pair's next warm start and, while the
    // pair stays apart, proves it again with one evaluation.
    memory.normal = g.normal;
    memory.r_star = 0.0;
    return false;
  }
  memory.normal = g.normal;
  if (!g.touching) {
    memory.r_star = 0.0;
    return false;
  }
  kin.normal = g.normal;
  kin.overlap = g.depth;
  kin.lever_i = g.point - p.x[i];
  kin.lever_j = g.point - p.x[j];
  // Elliptic Hertz through the Gaussian-curvature radius (Johnson 1985, eq. 4.25), taken at
  // first touch and held while the contact lasts: the normal force is then the gradient of
  // the Hertz potential (8/15) E* sqrt(R*) delta^(5/2), since d(delta) is the normal at the
  // contact point (envelope theorem), and the contact law is conservative.
  if (first_touch) memory.r_star = gaussian_curvature_radius(g);
  r_star = memory.r_star;
  return true;
}

// An ellipsoid against a plane wall, closed form: its lowest point along -normal
// (docs/ellipsoid-contact.md). Returns false when apart (then r_held = 0). Sets the overlap
// and lever of `kin` (the caller sets kin.normal = -wall.normal) and the Hertz radius, held
// from first touch in r_held, as for pairs.
inline bool shaped_wall_geometry(const PosedEllipsoid& posed, const Vec3& x, const PlaneWall& wall,
                                 double& r_held, ContactKinematics& kin) {
  const ContactGeometry g = posed_plane_contact(posed, Plane{wall.point, wall.normal}, r_held == 0.0);
  if (!g.touching) {
    r_held = 0.0;
    return false;
  }
  kin.overlap = g.depth;
  kin.lever_i = g.point - x;
  if (r_held == 0.0) r_held = gaussian_curvature_radius(g);
  return true;
}

}  // namespace upgrain::dem
