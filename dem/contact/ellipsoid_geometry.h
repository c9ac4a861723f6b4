#pragma once
// Contact geometry of three-axis ellipsoids: overlap depth, unit
// normal, contact points and principal curvatures for ellipsoid-ellipsoid, ellipsoid-sphere
// and ellipsoid-plane pairs. Algorithm, proofs and verification: docs/ellipsoid-contact.md.
//
// Definition of overlap (the only one used): the signed minimum translation distance
//   depth = min over unit n of f(n),  f(n) = n.(c1 - c2) + sqrt(n^T M1 n) + sqrt(n^T M2 n),
// M_i = R_i diag(a_i^2, b_i^2, c_i^2) R_i^T. f(n) is the support function of the Minkowski
// difference B1 - B2, so depth > 0 is the shortest translation of body 2 that separates the
// pair and depth < 0 is minus their distance. For spheres f(n) = n.(c1 - c2) + r1 + r2 is
// minimal at n = (c2 - c1)/|c2 - c1|, giving depth = r1 + r2 - |c2 - c1| exactly.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>

#include "dem/contact/contact_solver_settings.h"
#include "dem/core/types.h"

namespace upgrain::dem {

struct Ellipsoid {
  Vec3 centre = Vec3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> world, unit
  Vec3 semi_axes = Vec3::Ones();  // a >= b >= c along the body x, y, z axes (m)

  static Ellipsoid sphere(const Vec3& centre, double radius) {
    return {centre, Eigen::Quaterniond::Identity(), Vec3::Constant(radius)};
  }
  [[nodiscard]] bool is_sphere() const {
    return semi_axes.x() == semi_axes.y() && semi_axes.y() == semi_axes.z();
  }
};

// A wall: the solid half-space behind the plane; `normal` (unit) points into the granular
// domain, as in PlaneWall.
struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};

struct ContactGeometry {
  bool touching = false;
  double depth = 0.0;                 // > 0 overlap, < 0 gap (m)
  Vec3 normal = Vec3::UnitZ();        // unit, from body 1 to body 2
  Vec3 point = Vec3::Zero();          // mid-way between point1 and point2
  Vec3 point1 = Vec3::Zero();         // on body 1's surface, the deepest point of 1 towards 2
  Vec3 point2 = Vec3::Zero();         // on body 2's surface; point1 - point2 = depth * normal
  Vec3 lever1 = Vec3::Zero();         // point - centre of body 1 (torque arm)
  Vec3 lever2 = Vec3::Zero();         // point - centre of body 2 (0 for a plane)
  double curvature1[2] = {0.0, 0.0};  // principal curvatures of body 1 at point1 (1/m), k[0] >= k[1];
                                      // computed for touching pairs only (0 for a gap)
  double curvature2[2] = {0.0, 0.0};  // the same for body 2 at point2 (0 for a plane)
  Vec3 direction1 = Vec3::UnitX();    // principal direction of curvature1[0] (world, unit)
  Vec3 direction2 = Vec3::UnitX();    // principal direction of curvature2[0]
  int iterations = 0;                 // Newton steps taken, over all starts
  bool converged = true;              // the normal is a stationary point to round-off
  bool certified = true;              // the proof of global minimality holds (docs)
};

// Counters the caller reports in the run's log: nothing is dropped silently.
struct ContactSolverStats {
  std::int64_t calls = 0;
  std::int64_t warm_starts = 0;    // calls given an initial normal
  std::int64_t warm_rejected = 0;  // warm result not certified: solved again from cold
  std::int64_t newton_iterations = 0;
  std::int64_t fallbacks = 0;     // the multi-start fallback ran
  std::int64_t failures = 0;      // no start converged: best point returned, converged = false
  std::int64_t uncertified = 0;   // converged but deeper than the certificate covers
  std::int64_t proven_apart = 0;  // pairs rejected by proven_separated() before the solver
  // Pairs whose last proof of separation still held: the gap it proved exceeded both grains'
  // motion since (GrainPoses::motion), so no evaluation at all.
  std::int64_t still_apart = 0;

  ContactSolverStats& operator+=(const ContactSolverStats& o) {
    calls += o.calls;
    warm_starts += o.warm_starts;
    warm_rejected += o.warm_rejected;
    newton_iterations += o.newton_iterations;
    fallbacks += o.fallbacks;
    failures += o.failures;
    uncertified += o.uncertified;
    proven_apart += o.proven_apart;
    still_apart += o.still_apart;
    return *this;
  }
  // The counts of a span of a run: the totals at its end minus those at its start.
  ContactSolverStats& operator-=(const ContactSolverStats& o) {
    calls -= o.calls;
    warm_starts -= o.warm_starts;
    warm_rejected -= o.warm_rejected;
    newton_iterations -= o.newton_iterations;
    fallbacks -= o.fallbacks;
    failures -= o.failures;
    uncertified -= o.uncertified;
    proven_apart -= o.proven_apart;
    still_apart -= o.still_apart;
    return *this;
  }
};

// An ellipsoid with its rotation matrix R and shape matrix M = R diag(a^2, b^2, c^2) R^T
// computed once: the force loop poses every grain once per step instead of once per pair
// and call. Results are bitwise those of the Ellipsoid overloads (the pair frame's scaling
// is a power of two, so scaling M afterwards is exact).
struct PosedEllipsoid {
  Vec3 centre = Vec3::Zero();
  Mat3 rot = Mat3::Identity();
  Vec3 semi_axes = Vec3::Ones();
  Mat3 shape = Mat3::Identity();
  double major = 1.0;       // largest semi-axis a
  double minor = 1.0;       // smallest semi-axis c
  double min_radius = 1.0;  // c^2 / a: the smallest radius of curvature of the surface

  static PosedEllipsoid from(const Ellipsoid& e);
  // M = R diag(a^2, b^2, c^2) R^T (the one formula of both from() and GrainPoses).
  static Mat3 shape_of(const Mat3& rot, const Vec3& semi_axes);
  [[nodiscard]] bool is_sphere() const {
    return semi_axes.x() == semi_axes.y() && semi_axes.y() == semi_axes.z();
  }
};

// What the force loops need of a pair with at least one ellipsoid.
struct PairContact {
  double depth = 0.0;            // > 0 overlap, < 0 gap, or an upper bound of it when proven apart
  Vec3 normal = Vec3::UnitZ();   // from body 1 to body 2: the next step's warm start
  Vec3 lever1 = Vec3::Zero();    // contact point minus centre 1 (touching pairs)
  Vec3 lever2 = Vec3::Zero();    // contact point minus centre 2
  double gaussian_radius = 0.0;  // R_e at the contact (touching, when asked for), else 0
};

// The force loop's call (docs/ellipsoid-contact.md, "In the force loop"). With the pair's last
// normal m: f(m) < 0 proves the pair apart with one evaluation (f bounds the depth from above;
// counted in stats.proven_apart); otherwise Newton runs from m, straight-line code for the usual
// few small steps, the general solver of ellipsoid_contact() when a step is large, the model
// indefinite or the result not certified. Without a last normal: proven_separated()'s three
// directions, then the cold start. `radius` asks for the Gaussian-curvature radius (the contact
// law needs it only at first touch). Returns true when touching. `out.normal` is always set:
// the direction of the proof or the solver's normal.
bool posed_contact(const PosedEllipsoid& e1, const PosedEllipsoid& e2, const Vec3* last_normal, bool radius,
                   const ContactSolverSettings& settings, ContactSolverStats& stats, PairContact& out);

// One warm pair of posed_contacts_two(): its grains and last normal, and what the solve gives.
struct WarmPairSolve {
  const PosedEllipsoid* first = nullptr;
  const PosedEllipsoid* second = nullptr;
  Vec3 last_normal = Vec3::Zero();  // unit
  PairContact out;
  bool touching = false;
};

// Two warm pairs at once (the force loops' batches): as posed_contact() on each with radius
// false, the same results bit for bit and the same counts, with both Newton solves in the two
// lanes of a vector while both stay on the straight-line path (docs/ellipsoid-contact.md, "Two
// pairs at a time"). Precondition: each pair has an ellipsoid and its last normal is a unit
// vector (a warm pair); others go through posed_contact().
void posed_contacts_two(WarmPairSolve& pair_a, WarmPairSolve& pair_b, const ContactSolverSettings& settings,
                        ContactSolverStats& stats);

// Ellipsoid-plane on a posed ellipsoid, optionally without curvatures.
ContactGeometry posed_plane_contact(const PosedEllipsoid& e, const Plane& plane, bool curvatures);

// Ellipsoid-ellipsoid (either may be a sphere). `initial_normal`: the previous step's normal
// of a persisting pair (warm start); without it, a cold start from a few candidate normals.
// `settings`: the stopping rules (contact_solver_settings.h), the defaults unless a scene sets
// them.
ContactGeometry ellipsoid_contact(const Ellipsoid& e1, const Ellipsoid& e2, ContactSolverStats& stats,
                                  const std::optional<Vec3>& initial_normal = std::nullopt,
                                  const ContactSolverSettings& settings = {});

// The same without the sphere-sphere shortcut: always the support-function solver (tests).
ContactGeometry support_function_contact(const Ellipsoid& e1, const Ellipsoid& e2, ContactSolverStats& stats,
                                         const std::optional<Vec3>& initial_normal = std::nullopt,
                                         const ContactSolverSettings& settings = {});

// Ellipsoid-sphere: body 1 the ellipsoid, body 2 the sphere.
ContactGeometry ellipsoid_sphere_contact(const Ellipsoid& e, const Vec3& centre, double radius,
                                         ContactSolverStats& stats,
                                         const std::optional<Vec3>& initial_normal = std::nullopt,
                                         const ContactSolverSettings& settings = {});

// Sphere-sphere in closed form: depth = r1 + r2 - |c2 - c1|, normal = (c2 - c1)/|c2 - c1|.
ContactGeometry sphere_sphere_contact(const Vec3& c1, double r1, const Vec3& c2, double r2);

// Ellipsoid-plane in closed form: body 1 the ellipsoid, body 2 the wall, normal = -plane.normal,
// depth = sqrt(m^T M m) - m.(c - q) (m the plane normal, q its point).
ContactGeometry ellipsoid_plane_contact(const Ellipsoid& e, const Plane& plane);

// The support-function objective f(n) of the definition above, for any unit n (tests, broad
// phase). Computed in the pair's frame from c1 - c2 only.
double support_gap_function(const Ellipsoid& e1, const Ellipsoid& e2, const Vec3& n);

// ---- broad phase -------------------------------------------------------------------------

// Radius of the bounding sphere: the largest semi-axis.
inline double bounding_radius(const Ellipsoid& e) { return e.semi_axes.maxCoeff(); }

// True unless the bounding spheres, grown by `margin`, are apart.
inline bool bounding_spheres_overlap(const Ellipsoid& e1, const Ellipsoid& e2, double margin = 0.0) {
  const double reach = bounding_radius(e1) + bounding_radius(e2) + margin;
  return (e1.centre - e2.centre).squaredNorm() < reach * reach;
}

// Conservative rejection: f(n) >= depth for every unit n, so f(n) < -margin for any n proves
// the pair is apart by more than `margin`. Tries the centre-to-centre direction and the two
// surface normals where that line leaves each body. Never rejects a touching pair; returns
// false when it cannot prove separation (then run the narrow phase).
bool proven_separated(const Ellipsoid& e1, const Ellipsoid& e2, double margin = 0.0);

// ---- curvature -----------------------------------------------------------------------------

struct PrincipalCurvatures {
  double k[2] = {0.0, 0.0};        // k[0] >= k[1] > 0 (1/m)
  Vec3 direction = Vec3::UnitX();  // world principal direction of k[0]
};

// Principal curvatures at a surface point x of an ellipsoid: eigenvalues of the shape operator
// of g(y) = y^T A y - 1 (y body coordinates, A = diag(1/a^2, 1/b^2, 1/c^2)), i.e. of
// P A P / |A y| on the tangent plane (P the projector orthogonal to A y).
PrincipalCurvatures principal_curvatures(const Ellipsoid& e, const Vec3& surface_point);

// Effective Hertz radii from the two surfaces' curvatures at a contact (Johnson 1985, sec. 4.1):
// the relative curvatures A, B satisfy A + B = H1 + H2 (H = (k0 + k1)/2, the mean curvature) and
// (B - A)^2 = ((k1_0 - k1_1)^2 + (k2_0 - k2_1)^2 + 2 (k1_0 - k1_1)(k2_0 - k2_1) cos 2psi) / 4 with
// psi the angle between the principal directions (eq. 4.4).
struct RelativeCurvature {
  double a = 0.0, b = 0.0;  // A <= B (1/m)
};
RelativeCurvature relative_curvature(const ContactGeometry& g);

// Mean-curvature radius R* = 1/(H1 + H2) = 1/(A + B): exact for spheres (R1 R2/(R1 + R2)).
double mean_curvature_radius(const ContactGeometry& g);

// Gaussian-curvature equivalent radius R_e = 1/(2 sqrt(A B)) (Johnson 1985, eq. 4.25). The contact
// law uses this one: at equal overlap the sphere formula with R_e is within 1 % (B/A = 2) and
// 5 % (B/A = 5) of elliptic Hertz, with R* 4 % and 18 % low (docs/ellipsoid-contact.md).
double gaussian_curvature_radius(const ContactGeometry& g);

}  // namespace upgrain::dem
