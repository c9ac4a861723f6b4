#pragma once
// The geometry of ellipsoid contacts as the force loop uses it (dem/engine/force_loop.h):
// pairs with at least one ellipsoid and ellipsoids against walls (docs/ellipsoids.md).
#include <vector>

#include "dem/contact/contact_response.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/grain_poses.h"
#include "dem/core/plane_wall.h"

namespace upgrain::dem {

// The geometry of a pair with at least one ellipsoid (docs/ellipsoids.md), after the bounding
// spheres: unless the pair's last proof of separation still holds, posed_contact(), a separation
// proof at the pair's last normal and the support-function solver warm-started there. The pair's
// memory keeps the last normal of a near pair (the next step's warm start), the gap still proven
// for an apart one, and the Hertz radius of a touching one; its normal points from i to j. The
// force loops take their pairs in batches (a chunk of rows or pair slots) to solve them two at a
// time (shaped_pair_geometries).

// Separation budget (docs/ellipsoid-contact.md): the depth is at most f(m), and f(m) grows by
// at most the grains' motion bounds, so the gap proven at the last evaluation, less the motion
// since, is still a gap. A pair that stays apart is proven once, not every step. True when the
// pair is still apart without an evaluation.
inline bool still_apart(const GrainPoses& poses, std::size_t i, std::size_t j, ShapedContactMemory& memory,
                        ContactSolverStats& stats) {
  if (memory.gap_budget > 0.0) {
    memory.gap_budget -= poses.motion(i) + poses.motion(j);
    if (memory.gap_budget > 0.0) {
      ++stats.still_apart;
      return true;
    }
  }
  return false;
}

// The pair's memory after posed_contact() gave `c` (touching or not), and its kinematics.
inline bool finish_pair(const GrainPoses& poses, std::size_t i, std::size_t j, bool touching,
                        const PairContact& c, ShapedContactMemory& memory, ContactKinematics& kin,
                        double& r_star) {
  const bool first_touch = memory.r_star == 0.0;
  // The normal of the proof or the solver: the pair's next warm start.
  memory.normal = c.normal;
  if (!touching) {
    memory.r_star = 0.0;
    // -depth is the proven gap (f's round-off is below 1e-14 of the pair's size; the margin is
    // ten times that).
    memory.gap_budget = -c.depth - 1e-13 * (poses[i].major + poses[j].major);
    return false;
  }
  memory.gap_budget = 0.0;
  kin.normal = c.normal;
  kin.overlap = c.depth;
  kin.lever_i = c.lever1;
  kin.lever_j = c.lever2;
  // Elliptic Hertz through the Gaussian-curvature radius (Johnson 1985, eq. 4.25), taken at
  // first touch and held while the contact lasts: the normal force is then the gradient of
  // the Hertz potential (8/15) E* sqrt(R*) delta^(5/2), since d(delta) is the normal at the
  // contact point (envelope theorem), and the contact law is conservative.
  if (first_touch) memory.r_star = c.gaussian_radius;
  r_star = memory.r_star;
  return true;
}

// One pair of a batch, and its geometry.
struct ShapedPair {
  std::size_t i = 0, j = 0;
  ShapedContactMemory* memory = nullptr;
  bool touching = false;
  // When touching: the geometry part of its ContactKinematics, and the held Hertz radius.
  Vec3 normal = Vec3::Zero();
  double overlap = 0.0;
  Vec3 lever_i = Vec3::Zero(), lever_j = Vec3::Zero();
  double r_star = 0.0;

  // Its geometry into a contact's kinematics, and its Hertz radius.
  void kinematics(ContactKinematics& kin, double& radius) const {
    kin.normal = normal;
    kin.overlap = overlap;
    kin.lever_i = lever_i;
    kin.lever_j = lever_j;
    radius = r_star;
  }
};

// The geometry of every pair of `pairs` (after the bounding spheres): the separation budget,
// then posed_contact(), two pairs at once (posed_contacts_two: the same results bit for bit and
// the same counts) where both were touching at the last step, then each pair's memory.
void shaped_pair_geometries(const GrainPoses& poses, std::vector<ShapedPair>& pairs,
                            ContactSolverStats& stats);

// An ellipsoid against a plane wall, closed form: its lowest point along -normal
// (docs/ellipsoid-contact.md). Returns false when apart (then r_held = 0). Sets the overlap
// and lever of `kin` (the caller sets kin.normal = -wall.normal) and the Hertz radius, held
// from first touch in r_held, as for pairs.
[[gnu::always_inline]] inline bool shaped_wall_geometry(const PosedEllipsoid& posed, const PlaneWall& wall,
                                                        double& r_held, ContactKinematics& kin) {
  const ContactGeometry g = posed_plane_contact(posed, Plane{wall.point, wall.normal}, r_held == 0.0);
  if (!g.touching) {
    r_held = 0.0;
    return false;
  }
  kin.overlap = g.depth;
  kin.lever_i = g.lever1;
  if (r_held == 0.0) r_held = gaussian_curvature_radius(g);
  return true;
}

}  // namespace upgrain::dem
