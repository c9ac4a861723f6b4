#pragma once
// The geometry of pairs with at least one ellipsoid (sphere-ellipsoid and ellipsoid-ellipsoid,
// a sphere posed as an ellipsoid of equal axes) by the support-function solver, as the force
// loop uses it (dem/engine/force_loop.h, docs/ellipsoids.md): in batches, before the force
// pass, two pairs at a time where it can.
#include <cstddef>
#include <vector>

#include "dem/contact/contact_kinematics.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/geometry/shaped_pair.h"
#include "dem/contact/grain_poses.h"
#include "dem/core/contact_history.h"
#include "dem/core/particle_store.h"

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

// The pair's memory after posed_contact() gave `c` (touching or not), and its geometry.
inline void finish_pair(const GrainPoses& poses, const PairContact& c, bool touching, ShapedPair& s) {
  ShapedContactMemory& memory = *s.memory;
  const bool first_touch = memory.r_star == 0.0;
  // The normal of the proof or the solver: the pair's next warm start.
  memory.normal = c.normal;
  s.touching = touching;
  if (!touching) {
    memory.r_star = 0.0;
    // -depth is the proven gap (f's round-off is below 1e-14 of the pair's size; the margin is
    // ten times that).
    memory.gap_budget = -c.depth - 1e-13 * (poses[s.i].major + poses[s.j].major);
    return;
  }
  memory.gap_budget = 0.0;
  s.normal = c.normal;
  s.overlap = c.depth;
  s.lever_i = c.lever1;
  s.lever_j = c.lever2;
  // Elliptic Hertz through the Gaussian-curvature radius (Johnson 1985, eq. 4.25), taken at
  // first touch and held while the contact lasts: the normal force is then the gradient of
  // the Hertz potential (8/15) E* sqrt(R*) delta^(5/2), since d(delta) is the normal at the
  // contact point (envelope theorem), and the contact law is conservative.
  if (first_touch) memory.r_star = c.gaussian_radius;
  s.r_star = memory.r_star;
}

// The geometry of every pair of `pairs` (after the bounding spheres): the separation budget,
// then posed_contact(), two pairs at once (posed_contacts_two: the same results bit for bit and
// the same counts) where both were touching at the last step, then each pair's memory.
void shaped_pair_geometries(const GrainPoses& poses, std::vector<ShapedPair>& pairs,
                            const ContactSolverSettings& settings, ContactSolverStats& stats);

// The support-function rows of the pair-geometry table (pair_geometries.h).
struct SupportFunctionPair {
  static constexpr bool closed_form = false;
  static constexpr const char* name = "support function (sphere-ellipsoid, ellipsoid-ellipsoid)";
  static void solve(const GrainPoses& poses, std::vector<ShapedPair>& pairs,
                    const ContactSolverSettings& settings, ContactSolverStats& stats) {
    shaped_pair_geometries(poses, pairs, settings, stats);
  }

  // Grain i of `p` as the solver sees it: a sphere as an ellipsoid of equal axes.
  static Ellipsoid body(const ParticleStore& p, std::size_t i) {
    if (!p.oriented(i)) return Ellipsoid::sphere(p.x[i], p.radius[i]);
    return {p.x[i], p.orientation[i], p.semi_axes[i]};
  }
  // Grains i and j of `p` outside the force loop (body 1 is i, j moved by shift_j;
  // pair_contact()): a cold start, nothing held.
  static ContactGeometry contact(const ParticleStore& p, std::size_t i, std::size_t j, const Vec3& shift_j,
                                 ContactSolverStats& stats) {
    Ellipsoid j_body = body(p, j);
    j_body.centre += shift_j;
    return ellipsoid_contact(body(p, i), j_body, stats);
  }
};

}  // namespace upgrain::dem
