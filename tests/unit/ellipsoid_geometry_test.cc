// Ellipsoid contact geometry against independent long-double references:
// closed forms (spheres, coaxial tip-to-tip and face-to-face pairs), contacts constructed with
// a known depth and normal, and dense sampling of the sphere of normals. The full accuracy
// table of docs/ellipsoid-contact.md is DISABLED_AccuracyTable (1e5 pairs per shape):
//   unit_tests --gtest_also_run_disabled_tests --gtest_filter='*AccuracyTable*'
#include "dem/contact/ellipsoid_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "dem/contact/ellipsoid_reference.h"
#include "tests/unit/ellipsoid_cases.h"

namespace upgrain::dem {
namespace {

namespace ref = reference;
using ref::Real;
using namespace ellipsoid_cases;

// --- spheres --------------------------------------------------------------------------------

TEST(EllipsoidGeometry, SpheresReproduceTheSphereResult) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> r(1e-3, 2.5e-3), gap(-0.2, 0.2);
  ContactSolverStats stats;
  for (int i = 0; i < 1000 / kScale; ++i) {
    const double r1 = r(rng), r2 = r(rng);
    const Vec3 c1 = random_unit(rng) * 2.0;
    const Vec3 c2 = c1 + random_unit(rng) * (r1 + r2) * (1.0 - gap(rng));
    const double dist = (c2 - c1).norm();
    // The dispatching entry point takes the closed form: bit-identical.
    const ContactGeometry s = ellipsoid_contact(Ellipsoid::sphere(c1, r1), Ellipsoid::sphere(c2, r2), stats);
    EXPECT_EQ(s.depth, r1 + r2 - dist);
    EXPECT_EQ(s.normal, Vec3((c2 - c1) / dist));
    // The general support-function solver on spheres: the same to round-off of the inputs.
    const ContactGeometry g =
        support_function_contact(Ellipsoid::sphere(c1, r1), Ellipsoid::sphere(c2, r2), stats);
    EXPECT_NEAR(g.depth, r1 + r2 - dist, 4.0 * 2.2e-16 * (r1 + r2));
    EXPECT_LT((g.normal - s.normal).norm(), 1e-15);
    EXPECT_LE(g.iterations, 1);
    EXPECT_EQ(g.touching, s.touching);
    if (g.touching) {
      EXPECT_NEAR(mean_curvature_radius(g), r1 * r2 / (r1 + r2), 1e-14 * r1);
      EXPECT_NEAR(gaussian_curvature_radius(g), r1 * r2 / (r1 + r2), 1e-14 * r1);
    }
  }
  EXPECT_EQ(stats.failures, 0);
}

// --- closed forms: coaxial pairs --------------------------------------------------------------

// Coaxial tip-to-tip along the major axis: depth = a1 + a2 - |d|; face-to-face along the minor
// axis: depth = c1 + c2 - |d|. |d| is exact: c1 - c2 of two nearby doubles is exact (Sterbenz).
TEST(EllipsoidGeometry, CoaxialPairsMatchTheClosedForms) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> size(1e-3, 2.5e-3);
  ContactSolverStats stats;
  for (const Shape& shape : kShapes) {
    for (int axis : {0, 2}) {
      for (double delta_over_c : {1e-2, 1e-4, 1e-6, 1e-8}) {
        for (int i = 0; i < 50; ++i) {
          const Vec3 n = random_unit(rng);
          Ellipsoid e1, e2;
          e1.semi_axes = shape.ratio * size(rng);
          e2.semi_axes = shape.ratio * size(rng);
          e1.orientation = aligned(rng, Vec3::Unit(axis), n);
          e2.orientation = aligned(rng, Vec3::Unit(axis), n);
          e1.centre = random_unit(rng) * 2.0;
          const double c_min = std::min(e1.semi_axes.z(), e2.semi_axes.z());
          const double reach = e1.semi_axes[axis] + e2.semi_axes[axis];
          e2.centre = e1.centre + (reach - delta_over_c * c_min) * n;
          const ref::V3 d = ref::widen(e2.centre) - ref::widen(e1.centre);
          const Real exact = static_cast<Real>(reach) - d.norm();
          const ContactGeometry g = ellipsoid_contact(e1, e2, stats);
          ASSERT_TRUE(g.converged);
          EXPECT_TRUE(g.touching);
          EXPECT_LE(std::abs(g.depth - exact), 1e-12L * c_min)
              << shape.name << " axis " << axis << " delta/c " << delta_over_c;
          EXPECT_LE(angle(g.normal, d.normalized()), 1e-8L);
        }
      }
    }
  }
  EXPECT_EQ(stats.failures, 0);
}

// --- constructed contacts ----------------------------------------------------------------------

struct CellResult {
  Real max_abs_over_c = 0;  // max |depth - exact| / c
  Real max_rel = 0;         // max |depth - exact| / exact
  Real max_angle = 0;       // max normal error (rad)
  int misses = 0, false_contacts = 0, uncertified = 0, failures = 0;
  double mean_iterations = 0;
};

CellResult run_cell(std::mt19937_64& rng, const Shape& shape, Orientation o, double delta_over_c, int count) {
  CellResult r;
  ContactSolverStats stats;
  for (int i = 0; i < count; ++i) {
    const Case k = make_case(rng, shape, o, delta_over_c);
    const ContactGeometry g = ellipsoid_contact(k.e1, k.e2, stats);
    const Real err = std::abs(g.depth - k.depth);
    r.max_abs_over_c = std::max(r.max_abs_over_c, err / k.c_min);
    r.max_rel = std::max(r.max_rel, err / std::abs(k.depth));
    r.max_angle = std::max(r.max_angle, angle(g.normal, k.normal));
    r.misses += (k.depth > 0 && !g.touching);
    r.false_contacts += (k.depth < 0 && g.touching);
    r.uncertified += !g.certified;
    r.mean_iterations += g.iterations;
  }
  r.failures = static_cast<int>(stats.failures);
  r.mean_iterations /= count;
  return r;
}

TEST(EllipsoidGeometry, ConstructedContactsMeetTheAccuracyTargets) {
  std::mt19937_64 rng(3);
  for (const Shape& shape : kShapes) {
    for (Orientation o : {Orientation::random, Orientation::face_to_face, Orientation::tip_to_tip}) {
      for (double delta_over_c : {1e-2, 1e-4, 1e-6, 1e-8}) {
        const CellResult r = run_cell(rng, shape, o, delta_over_c, 200 / kScale);
        SCOPED_TRACE(std::string(shape.name) + " " + name(o) + " delta/c " + std::to_string(delta_over_c));
        EXPECT_LE(r.max_abs_over_c, 1e-12L);
        EXPECT_LE(r.max_angle, 1e-8L);
        EXPECT_EQ(r.misses, 0);
        EXPECT_EQ(r.uncertified, 0);
        EXPECT_EQ(r.failures, 0);
      }
    }
  }
}

// The contact points: point1 on body 1, point2 on body 2, point1 - point2 = depth n, and the
// mid-point inside both bodies for an overlap (a proof of contact independent of f).
TEST(EllipsoidGeometry, ContactPointsLieOnTheSurfaces) {
  std::mt19937_64 rng(4);
  ContactSolverStats stats;
  for (const Shape& shape : kShapes) {
    for (int i = 0; i < 200 / kScale; ++i) {
      const Case k = make_case(rng, shape, Orientation::random, 1e-3);
      const ContactGeometry g = ellipsoid_contact(k.e1, k.e2, stats);
      const ref::Body b1 = ref::body(k.e1), b2 = ref::body(k.e2);
      // |g| ~ 2 |dx|/a: 1e-11 covers the rounding of a point 2 m from the origin
      EXPECT_LT(std::abs(ref::inside(b1, ref::widen(g.point1))), 1e-10L);
      EXPECT_LT(std::abs(ref::inside(b2, ref::widen(g.point2))), 1e-10L);
      EXPECT_LT((g.point1 - g.point2 - g.depth * g.normal).norm(), 1e-14);
      EXPECT_LT(ref::inside(b1, ref::widen(g.point)), 0.0L);
      EXPECT_LT(ref::inside(b2, ref::widen(g.point)), 0.0L);
    }
  }
}

// The construction's optimum is the global one, found by dense sampling (no use of the
// certificate D4); the solver agrees with both.
TEST(EllipsoidGeometry, DenseReferenceConfirmsTheConstruction) {
  std::mt19937_64 rng(5);
  ContactSolverStats stats;
  for (const Shape& shape : kShapes) {
    for (Orientation o : {Orientation::random, Orientation::face_to_face, Orientation::tip_to_tip}) {
      for (int i = 0; i < 6 / (kScale > 1 ? 3 : 1); ++i) {
        const Case k = make_case(rng, shape, o, i % 2 ? 1e-2 : -1e-5);
        const ref::Minimum m = ref::dense_minimum(ref::body(k.e1), ref::body(k.e2));
        EXPECT_LE(std::abs(m.f - k.depth), 1e-14L * k.c_min) << shape.name << " " << name(o);
        EXPECT_LE(std::acos(std::min<Real>(1, m.n.dot(k.normal))), 1e-8L);
        const ContactGeometry g = ellipsoid_contact(k.e1, k.e2, stats);
        EXPECT_LE(std::abs(g.depth - m.f), 1e-12L * k.c_min);
      }
    }
  }
}

// Pairs placed at random inside each other's bounding spheres (deep overlaps, gaps, anything):
// the solver finds the global minimum of the dense reference.
TEST(EllipsoidGeometry, RandomPairsMatchTheDenseReference) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> size(1e-3, 2.5e-3), reach(0.0, 1.0);
  ContactSolverStats stats;
  for (const Shape& shape : kShapes) {
    for (int i = 0; i < 30 / kScale; ++i) {
      Ellipsoid e1, e2;
      e1.semi_axes = shape.ratio * size(rng);
      e2.semi_axes = shape.ratio * size(rng);
      e1.orientation = random_rotation(rng);
      e2.orientation = random_rotation(rng);
      e1.centre = random_unit(rng) * 2.0;
      e2.centre = e1.centre + random_unit(rng) * reach(rng) * (e1.semi_axes.x() + e2.semi_axes.x());
      const double c_min = std::min(e1.semi_axes.z(), e2.semi_axes.z());
      const ref::Minimum m = ref::dense_minimum(ref::body(e1), ref::body(e2), 20000, 8);
      const ContactGeometry g = ellipsoid_contact(e1, e2, stats);
      EXPECT_TRUE(g.converged);
      EXPECT_LE(std::abs(g.depth - m.f), 1e-12L * c_min) << shape.name << " depth/c " << m.f / c_min;
    }
  }
  EXPECT_EQ(stats.failures, 0);
}

// --- near touching: no missed and no false contacts ---------------------------------------------

struct Classification {
  int misses = 0, false_contacts = 0, unproven = 0;
};

// Signed overlaps log-uniform in 1e-8 c .. 1e-2 c, random orientations, cold starts. Each answer
// also carries its own proof, checked in long double: a separating normal (f(n) < 0) for a gap,
// a common interior point (the mid-point) for a contact.
Classification classify(std::mt19937_64& rng, const Shape& shape, int count, ContactSolverStats& stats) {
  std::uniform_real_distribution<double> exponent(-8.0, -2.0);
  std::bernoulli_distribution overlap(0.5);
  Classification c;
  for (int i = 0; i < count; ++i) {
    const double delta = (overlap(rng) ? 1.0 : -1.0) * std::pow(10.0, exponent(rng));
    const auto o = static_cast<Orientation>(i % 3);
    const Case k = make_case(rng, shape, o, delta);
    const ContactGeometry g = ellipsoid_contact(k.e1, k.e2, stats);
    c.misses += (k.depth > 0 && !g.touching);
    c.false_contacts += (k.depth < 0 && g.touching);
    const ref::Body b1 = ref::body(k.e1), b2 = ref::body(k.e2);
    const bool proven =
        g.touching ? (ref::inside(b1, ref::widen(g.point)) < 0 && ref::inside(b2, ref::widen(g.point)) < 0)
                   : ref::f(b1, b2, ref::widen(g.normal).normalized()) < 0;
    c.unproven += !proven;
  }
  return c;
}

TEST(EllipsoidGeometry, NearTouchingPairsAreNeverMissedNorFalse) {
  std::mt19937_64 rng(7);
  for (const Shape& shape : kShapes) {
    ContactSolverStats stats;
    const Classification c = classify(rng, shape, 10000 / kScale, stats);
    EXPECT_EQ(c.misses, 0) << shape.name;
    EXPECT_EQ(c.false_contacts, 0) << shape.name;
    EXPECT_EQ(c.unproven, 0) << shape.name;
    EXPECT_EQ(stats.failures, 0) << shape.name;
  }
}

// --- warm start, failures, plane, curvature, broad phase -----------------------------------------

// A persisting contact one step later: body 2 moved by `move` c and both bodies turned by `move`
// rad. A DEM step moves far less than 1e-4 (docs); 1e-3 is the stress case.
TEST(EllipsoidGeometry, WarmStartConvergesInThreeIterations) {
  std::mt19937_64 rng(8);
  for (double move : {1e-4, 1e-3}) {
    int worst = 0, total = 0, count = 0;
    for (const Shape& shape : kShapes) {
      for (Orientation o : {Orientation::random, Orientation::face_to_face, Orientation::tip_to_tip}) {
        for (int i = 0; i < 200 / kScale; ++i) {
          Case k = make_case(rng, shape, o, 1e-3);
          ContactSolverStats stats;
          const ContactGeometry before = ellipsoid_contact(k.e1, k.e2, stats);
          k.e2.centre += random_unit(rng) * move * k.c_min;
          k.e1.orientation = (Eigen::AngleAxisd(move, random_unit(rng)) * k.e1.orientation).normalized();
          k.e2.orientation = (Eigen::AngleAxisd(move, random_unit(rng)) * k.e2.orientation).normalized();
          const ContactGeometry warm = ellipsoid_contact(k.e1, k.e2, stats, before.normal);
          const ContactGeometry cold = ellipsoid_contact(k.e1, k.e2, stats);
          worst = std::max(worst, warm.iterations);
          total += warm.iterations;
          ++count;
          EXPECT_TRUE(warm.certified);
          EXPECT_EQ(stats.warm_rejected, 0);
          EXPECT_NEAR(warm.depth, cold.depth, 1e-13 * k.c_min);
          EXPECT_LT((warm.normal - cold.normal).norm(), 1e-9);
        }
      }
    }
    std::printf("warm start after a move of %g: mean %.2f, max %d iterations\n", move,
                static_cast<double>(total) / count, worst);
    EXPECT_LE(worst, move < 5e-4 ? 3 : 4);
    EXPECT_LE(static_cast<double>(total) / count, 3.0);
  }
}

// The stopping rules (ContactSolverSettings): a looser gradient bound stops Newton earlier, on
// the force loop's warm path (a normal 1e-4 rad from the exact one) and from cold, and the error
// it leaves is first order in the bound for the normal, second order for the depth
// (docs/ellipsoid-contact.md, "Stopping rules"): at a gradient |g| <= tau eps size the normal is
// off by at most about |g| / lambda_min, and the tangent Hessian's eigenvalues lie between
// rho - f and R_max - f (rho = c1^2/a1 + c2^2/a2 and R_max = a1^2/c1 + a2^2/c2, the smallest and
// largest radii of curvature of the Minkowski difference, D4), so the depth is off by at most
// about R_max/2 times the normal's error squared. A cap below the steps a cold start needs shows
// up as counted failures.
struct StopResult {
  Real depth = 0, normal = 0;  // largest |depth - exact| / c, largest normal angle
  // Largest error over its bound above, per pair (round-off allowed for).
  Real normal_over_bound = 0, depth_over_bound = 0;
  double cold_iterations = 0, warm_iterations = 0;
  std::int64_t failures = 0;
};

StopResult solve_with(const ContactSolverSettings& settings, int count) {
  std::mt19937_64 rng(11);
  StopResult r;
  ContactSolverStats cold_stats, warm_stats;
  for (int i = 0; i < count; ++i) {
    const Case k = make_case(rng, kShapes[i % 3], Orientation::random, 1e-3);
    const PosedEllipsoid p1 = PosedEllipsoid::from(k.e1), p2 = PosedEllipsoid::from(k.e2);
    const Vec3 n = k.normal.cast<double>().normalized();
    const Vec3 start = Eigen::AngleAxisd(1e-4, n.cross(random_unit(rng)).normalized()) * n;
    PairContact cold, warm;
    posed_contact(p1, p2, nullptr, true, settings, cold_stats, cold);
    posed_contact(p1, p2, &start, false, settings, warm_stats, warm);
    const Vec3 a1 = k.e1.semi_axes, a2 = k.e2.semi_axes;
    const double size = (k.e1.centre - k.e2.centre).lpNorm<1>() + a1.maxCoeff() + a2.maxCoeff();
    const double rho =
        a1.minCoeff() * a1.minCoeff() / a1.maxCoeff() + a2.minCoeff() * a2.minCoeff() / a2.maxCoeff();
    const double r_max =
        a1.maxCoeff() * a1.maxCoeff() / a1.minCoeff() + a2.maxCoeff() * a2.maxCoeff() / a2.minCoeff();
    const double eps = std::numeric_limits<double>::epsilon();
    const double normal_bound = settings.gradient_tolerance * eps * size / rho + 1e-11;
    const double depth_bound = 0.5 * r_max * normal_bound * normal_bound + 64 * eps * size;
    for (const PairContact* c : {&cold, &warm}) {
      const Real depth_error = std::abs(static_cast<Real>(c->depth) - k.depth);
      const Real normal_error = angle(c->normal, k.normal);
      r.depth = std::max(r.depth, depth_error / k.c_min);
      r.normal = std::max(r.normal, normal_error);
      r.normal_over_bound = std::max(r.normal_over_bound, normal_error / normal_bound);
      r.depth_over_bound = std::max(r.depth_over_bound, depth_error / depth_bound);
    }
  }
  r.cold_iterations = static_cast<double>(cold_stats.newton_iterations) / count;
  r.warm_iterations = static_cast<double>(warm_stats.newton_iterations) / count;
  r.failures = cold_stats.failures + warm_stats.failures;
  return r;
}

TEST(EllipsoidGeometry, StoppingRulesTradeIterationsForError) {
  const int count = 600 / kScale;
  const StopResult exact = solve_with({}, count);
  EXPECT_LE(exact.depth, 1e-12L);
  EXPECT_LE(exact.normal, 1e-8L);
  EXPECT_EQ(exact.failures, 0);
  ContactSolverSettings loose;
  loose.gradient_tolerance = 1e10;  // |g| <= 2.2e-6 size
  const StopResult l = solve_with(loose, count);
  std::printf("tolerance 16: depth error %.2Le c, normal %.2Le rad, %.2f cold / %.2f warm steps\n",
              exact.depth, exact.normal, exact.cold_iterations, exact.warm_iterations);
  std::printf("tolerance 1e10: depth error %.2Le c, normal %.2Le rad, %.2f cold / %.2f warm steps\n", l.depth,
              l.normal, l.cold_iterations, l.warm_iterations);
  EXPECT_LT(l.cold_iterations, exact.cold_iterations);
  EXPECT_LT(l.warm_iterations, exact.warm_iterations);
  EXPECT_GT(l.normal, 100 * exact.normal);  // the bound is felt
  std::printf("error over its bound: normal %.2Lf, depth %.2Lf (tolerance 16: %.2Lf, %.2Lf)\n",
              l.normal_over_bound, l.depth_over_bound, exact.normal_over_bound, exact.depth_over_bound);
  EXPECT_LE(l.normal_over_bound, 1.0L);
  EXPECT_LE(l.depth_over_bound, 1.0L);
  EXPECT_LE(exact.normal_over_bound, 1.0L);
  EXPECT_LE(exact.depth_over_bound, 1.0L);
  EXPECT_EQ(l.failures, 0);
  ContactSolverSettings capped;
  capped.max_iterations = 2;  // below the 3-4 steps of a cold start
  const StopResult c = solve_with(capped, count);
  EXPECT_GT(c.failures, 0);
  EXPECT_GT(c.depth, exact.depth);
}

TEST(EllipsoidGeometry, FailuresAndDeepOverlapsAreCounted) {
  ContactSolverStats stats;
  Ellipsoid e1, e2;
  e1.semi_axes = Vec3(1e-3, 0.2e-3, 0.1e-3);
  e2.semi_axes = e1.semi_axes;
  e2.centre = Vec3(std::nan(""), 0.0, 0.0);
  const ContactGeometry bad = ellipsoid_contact(e1, e2, stats);
  EXPECT_FALSE(bad.converged);
  EXPECT_FALSE(bad.touching);
  EXPECT_EQ(stats.failures, 1);
  EXPECT_EQ(stats.fallbacks, 1);
  // Concentric crossed needles: overlap of the order of the size, beyond the certificate.
  e2.centre = Vec3::Zero();
  e2.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Vec3::UnitZ()));
  const ContactGeometry deep = ellipsoid_contact(e1, e2, stats);
  EXPECT_TRUE(deep.converged);
  EXPECT_FALSE(deep.certified);
  EXPECT_EQ(stats.uncertified, 1);
  EXPECT_EQ(stats.failures, 1);
  const ref::Minimum m = ref::dense_minimum(ref::body(e1), ref::body(e2), 20000, 8);
  EXPECT_NEAR(deep.depth, static_cast<double>(m.f), 1e-12 * 1e-4);
}

TEST(EllipsoidGeometry, EllipsoidPlaneAndEllipsoidSphere) {
  std::mt19937_64 rng(9);
  ContactSolverStats stats;
  // A 1:1:0.1 disc lying on its face on the floor: depth c - z, normal -z.
  Ellipsoid disc;
  disc.semi_axes = Vec3(2e-3, 2e-3, 0.2e-3);
  disc.centre = Vec3(1.9, -1.2, 0.2e-3 - 1e-9);
  const ContactGeometry flat = ellipsoid_plane_contact(disc, Plane{});
  EXPECT_EQ(flat.depth, 0.2e-3 - disc.centre.z());  // exact (Sterbenz)
  EXPECT_EQ(flat.normal, Vec3(0, 0, -1));
  EXPECT_NEAR(flat.curvature1[0], 0.2e-3 / 4e-6, 1e-9);
  EXPECT_NEAR(flat.curvature2[0], 0.0, 0.0);
  for (int i = 0; i < 200; ++i) {
    Ellipsoid e;
    e.semi_axes = kShapes[i % 3].ratio * 2e-3;
    e.orientation = random_rotation(rng);
    e.centre = random_unit(rng) * 2.0;
    const Plane plane{e.centre + random_unit(rng) * 1e-3, random_unit(rng)};
    const ref::Body b = ref::body(e);
    const ref::V3 m = ref::widen(plane.normal);
    const Real exact = std::sqrt(m.dot(b.m * m)) - m.dot(b.centre - ref::widen(plane.point));
    const ContactGeometry g = ellipsoid_plane_contact(e, plane);
    EXPECT_LE(std::abs(g.depth - exact), 1e-12L * 2e-4);
    EXPECT_LT(std::abs(plane.normal.dot(g.point2 - plane.point)), 1e-15);
    // Ellipsoid-sphere: a constructed contact with body 2 a sphere.
    Case k = make_case(rng, kShapes[i % 3], Orientation::random, 1e-6);
    k.e2 = Ellipsoid::sphere(Vec3::Zero(), 1.5e-3);
    const ref::V3 c2 = ref::construct_centre2(ref::body(k.e1), ref::body(k.e2), k.normal, 1e-6L * k.c_min);
    const Vec3 c2d = c2.cast<double>();
    const Real depth = 1e-6L * k.c_min - k.normal.dot(ref::widen(c2d) - c2);
    const ContactGeometry s = ellipsoid_sphere_contact(k.e1, c2d, 1.5e-3, stats);
    EXPECT_LE(std::abs(s.depth - depth), 1e-12L * k.c_min);
    EXPECT_LE(angle(s.normal, k.normal), 1e-8L);
    EXPECT_NEAR(s.curvature2[0], 1.0 / 1.5e-3, 1e-9);
  }
  EXPECT_EQ(stats.failures, 0);
}

// Principal curvatures at the vertices: at (a, 0, 0) they are a/c^2 and a/b^2, at (0, 0, c)
// c/b^2 and c/a^2; the Gaussian curvature anywhere is 1/(a b c)^2 / |A y|^4 ... checked at the
// vertices only, and against the support-function Hessian in general via the contact.
TEST(EllipsoidGeometry, PrincipalCurvatures) {
  Ellipsoid e;
  e.semi_axes = Vec3(3.0, 2.0, 1.0);
  e.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  e.centre = Vec3(2.0, -1.0, 0.5);
  const Mat3 rot = e.orientation.toRotationMatrix();
  const PrincipalCurvatures tip = principal_curvatures(e, e.centre + 3.0 * rot.col(0));
  EXPECT_NEAR(tip.k[0], 3.0, 1e-14);
  EXPECT_NEAR(tip.k[1], 0.75, 1e-14);
  EXPECT_NEAR(std::abs(tip.direction.dot(rot.col(2))), 1.0, 1e-14);
  const PrincipalCurvatures face = principal_curvatures(e, e.centre + 1.0 * rot.col(2));
  EXPECT_NEAR(face.k[0], 0.25, 1e-14);
  EXPECT_NEAR(face.k[1], 1.0 / 9.0, 1e-14);
  // Gaussian curvature K = 1 / (a^2 b^2 c^2 |A y|^4) at a general surface point.
  const Vec3 y = Vec3(1.0, 1.0, 0.5).cwiseProduct(e.semi_axes).normalized().cwiseProduct(e.semi_axes);
  const Vec3 yy = y / y.cwiseQuotient(e.semi_axes).norm();  // on the surface
  const PrincipalCurvatures k = principal_curvatures(e, e.centre + rot * yy);
  const double ay = yy.cwiseQuotient(e.semi_axes.cwiseAbs2()).norm();
  EXPECT_NEAR(k.k[0] * k.k[1], 1.0 / (36.0 * std::pow(ay, 4)), 1e-13);
}

TEST(EllipsoidGeometry, BroadPhaseIsConservative) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> exponent(-8.0, -1.0);
  int rejected = 0, separated = 0;
  for (const Shape& shape : kShapes) {
    for (int i = 0; i < 3000 / kScale; ++i) {
      const double delta = (i % 2 ? 1.0 : -1.0) * std::pow(10.0, exponent(rng));
      const Case k = make_case(rng, shape, static_cast<Orientation>(i % 3), delta);
      if (k.depth > 0) {
        ASSERT_TRUE(bounding_spheres_overlap(k.e1, k.e2));
        ASSERT_FALSE(proven_separated(k.e1, k.e2));
      } else {
        ++separated;
        rejected += proven_separated(k.e1, k.e2);
      }
    }
  }
  std::printf("broad phase: %d of %d separated near-touching pairs rejected cheaply\n", rejected, separated);
}

// --- the accuracy table of docs/ellipsoid-contact.md ---------------------------------------------

TEST(EllipsoidGeometry, DISABLED_AccuracyTable) {
  std::mt19937_64 rng(11);
  const int per_cell = 100000 / 12;  // 1e5 per shape over 3 orientations x 4 overlaps
  std::printf(
      "| shape | orientation | overlap/c | max rel. error | max error/c | max normal error (rad) | "
      "misses | mean iterations |\n|---|---|---|---|---|---|---|---|\n");
  for (const Shape& shape : kShapes) {
    for (Orientation o : {Orientation::random, Orientation::face_to_face, Orientation::tip_to_tip}) {
      for (double delta_over_c : {1e-2, 1e-4, 1e-6, 1e-8}) {
        const CellResult r = run_cell(rng, shape, o, delta_over_c, per_cell);
        std::printf("| %s | %s | %.0e | %.1Le | %.1Le | %.1Le | %d | %.2f |\n", shape.name, name(o),
                    delta_over_c, r.max_rel, r.max_abs_over_c, r.max_angle, r.misses, r.mean_iterations);
        EXPECT_LE(r.max_abs_over_c, 1e-12L);
        EXPECT_LE(r.max_angle, 1e-8L);
        EXPECT_EQ(r.misses + r.failures + r.uncertified, 0);
      }
    }
  }
  std::printf(
      "\n| shape | near-touching pairs | misses | false contacts | unproven | fallbacks | failures |\n"
      "|---|---|---|---|---|---|---|\n");
  for (const Shape& shape : kShapes) {
    ContactSolverStats stats;
    const Classification c = classify(rng, shape, 100000, stats);
    std::printf("| %s | 100000 | %d | %d | %d | %lld | %lld |\n", shape.name, c.misses, c.false_contacts,
                c.unproven, static_cast<long long>(stats.fallbacks), static_cast<long long>(stats.failures));
    EXPECT_EQ(c.misses + c.false_contacts + c.unproven, 0);
  }
}

}  // namespace
}  // namespace upgrain::dem
