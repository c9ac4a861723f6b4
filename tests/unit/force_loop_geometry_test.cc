// The ellipsoid geometry as the force loops use it (docs/ellipsoid-contact.md, "In the force
// loop"): posed grains (GrainPoses), the straight-line warm Newton path of posed_contact(), and
// the separation budget of shaped_pair_geometry(). Checked against the long-double references
// of ellipsoid_reference.h and against the general solver of ellipsoid_contact().
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "dem/contact/ellipsoid_reference.h"
#include "dem/contact/geometry/support_function_pair.h"
#include "dem/contact/grain_poses.h"
#include "tests/unit/ellipsoid_cases.h"

namespace upgrain::dem {
namespace {

namespace ref = reference;
using ref::Real;
using namespace ellipsoid_cases;

// A two-grain store holding a pair (ids 1 and 2), to pose it as the force loop does.
ParticleStore store_of(const Ellipsoid& e1, const Ellipsoid& e2) {
  ParticleStore p;
  p.add_ellipsoid(1, {e1.semi_axes, 2650.0, e1.orientation}, {e1.centre, Vec3::Zero(), Vec3::Zero()});
  p.add_ellipsoid(2, {e2.semi_axes, 2650.0, e2.orientation}, {e2.centre, Vec3::Zero(), Vec3::Zero()});
  return p;
}

// Moves a grain by `move` (m) and turns it by `turn` (rad), both in random directions.
void nudge(std::mt19937_64& rng, Ellipsoid& e, double move, double turn) {
  e.centre += random_unit(rng) * move;
  e.orientation = (Eigen::AngleAxisd(turn, random_unit(rng)) * e.orientation).normalized();
}

// A warm pair, as in a run: the normal of the previous step, then the grains moved by up to
// 1e-4 of c and turned by up to 1e-4 rad. The force loop's answer (the straight-line path when it
// applies) meets the same targets as ellipsoid_contact() against the exact depth and normal of
// the constructed contact, and the levers end at one point.
TEST(ForceLoopGeometry, WarmPairsMeetTheAccuracyTargets) {
  std::mt19937_64 rng(21);
  for (const Shape& shape : kShapes) {
    for (Orientation o : {Orientation::random, Orientation::face_to_face, Orientation::tip_to_tip}) {
      Real worst_depth = 0, worst_angle = 0, worst_lever = 0;
      ContactSolverStats stats;
      for (double move : {1e-8, 1e-6, 1e-4}) {
        for (int i = 0; i < 100 / kScale; ++i) {
          const Case k = make_case(rng, shape, o, 1e-3);
          // The previous step: the same pair before the move.
          Ellipsoid b1 = k.e1, b2 = k.e2;
          nudge(rng, b1, move * k.c_min, move);
          nudge(rng, b2, move * k.c_min, move);
          ContactSolverStats before_stats;
          const Vec3 previous = ellipsoid_contact(b1, b2, before_stats).normal;
          GrainPoses poses;
          poses.update(store_of(k.e1, k.e2));
          PairContact c;
          ASSERT_TRUE(posed_contact(poses[0], poses[1], &previous, false, {}, stats, c));
          worst_depth = std::max(worst_depth, std::abs(static_cast<Real>(c.depth) - k.depth) / k.c_min);
          worst_angle = std::max(worst_angle, angle(c.normal, k.normal));
          // lever1 - lever2 = c2 - c1, to the rounding of the levers (size ~ a).
          worst_lever = std::max(
              worst_lever,
              static_cast<Real>((c.lever1 - c.lever2 + (k.e1.centre - k.e2.centre)).norm()) / k.c_min);
          // The contact point is inside both bodies (a proof of contact independent of f).
          const ref::V3 point = ref::widen(k.e1.centre) + ref::widen(c.lever1);
          EXPECT_LT(ref::inside(ref::body(k.e1), point), 0.0L);
          EXPECT_LT(ref::inside(ref::body(k.e2), point), 0.0L);
        }
      }
      SCOPED_TRACE(std::string(shape.name) + " " + name(o));
      std::printf("%s %s: depth error/c %.1Le, normal %.1Le rad, lever closure/c %.1Le, %.2f Newton steps\n",
                  shape.name, name(o), worst_depth, worst_angle, worst_lever,
                  static_cast<double>(stats.newton_iterations) / static_cast<double>(stats.calls));
      EXPECT_LE(worst_depth, 1e-12L);
      EXPECT_LE(worst_angle, 1e-8L);
      EXPECT_LE(worst_lever, 1e-14L);
      EXPECT_EQ(stats.fallbacks, 0);
      EXPECT_EQ(stats.failures, 0);
      EXPECT_EQ(stats.uncertified, 0);
    }
  }
}

// The motion bound of GrainPoses: for any unit n, the support value h(n) = n.c + sqrt(n^T M n)
// of a grain changes between two poses by at most motion(i) (evaluated in long double from the
// posed matrices), and the bound is not loose by more than a few times. A grain whose index now
// holds another grain has no bound.
TEST(ForceLoopGeometry, MotionBoundsTheChangeOfTheSupportFunction) {
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> size(1e-3, 2.5e-3), log_move(-12.0, -3.0);
  int checked = 0;
  for (const Shape& shape : kShapes) {
    for (int i = 0; i < 200 / kScale; ++i) {
      Ellipsoid e1{random_unit(rng) * 2.0, random_rotation(rng), shape.ratio * size(rng)};
      Ellipsoid e2 = e1;
      e2.centre += random_unit(rng);
      GrainPoses poses;
      poses.update(store_of(e1, e2));
      const PosedEllipsoid old = poses[0];
      const double move = std::pow(10.0, log_move(rng)) * e1.semi_axes.x();
      const double turn = i % 3 == 0 ? 0.0 : std::pow(10.0, log_move(rng));
      nudge(rng, e1, i % 3 == 1 ? 0.0 : move, turn);
      poses.update(store_of(e1, e2));
      const PosedEllipsoid& now = poses[0];
      const double bound = poses.motion(0);
      ASSERT_TRUE(std::isfinite(bound));
      Real largest = 0;
      auto h = [](const PosedEllipsoid& e, const ref::V3& n) {
        const ref::M3 m = e.shape.cast<Real>();
        return n.dot(ref::widen(e.centre)) + std::sqrt(n.dot(m * n));
      };
      for (int k = 0; k < 400; ++k) {
        const ref::V3 n = ref::widen(random_unit(rng)).normalized();
        largest = std::max(largest, std::abs(h(now, n) - h(old, n)));
      }
      EXPECT_LE(largest, static_cast<Real>(bound));
      if (largest > 1e-13L * e1.semi_axes.x()) {  // above the margins: the bound is useful
        EXPECT_GE(largest, 0.1L * static_cast<Real>(bound));
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 300 / kScale);
  // Reordered: index 0 now holds grain 2.
  Ellipsoid a{Vec3::Zero(), Eigen::Quaterniond::Identity(), Vec3(1e-3, 0.8e-3, 0.6e-3)}, b = a;
  b.centre.x() = 0.01;
  GrainPoses poses;
  poses.update(store_of(a, b));
  ParticleStore swapped = store_of(a, b);
  swapped.permute({1, 0});
  poses.update(swapped);
  EXPECT_EQ(poses.motion(0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(poses.motion(1), std::numeric_limits<double>::infinity());
  poses.update(swapped);  // unmoved: only the rounding margin
  EXPECT_LE(poses.motion(0), 1e-13 * a.semi_axes.x());
}

// The separation budget never hides a contact: pairs drift towards each other and apart again,
// turning, over many steps, with the force loop's memory (shaped_pair_geometries()); at every step
// the general solver says whether the pair touches. The budget must skip evaluations (else the
// test proves nothing) and never skip a touching pair; a reordered store (as after a neighbour-list
// rebuild) voids the budgets.
TEST(ForceLoopGeometry, SeparationBudgetNeverHidesAContact) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> size(1e-3, 2.5e-3), unit(0.0, 1.0);
  long steps = 0, skipped = 0, touching_steps = 0;
  for (const Shape& shape : kShapes) {
    // Debug and sanitizer builds: fewer pairs, each over the whole approach and retreat.
    for (int pair = 0; pair < (kScale > 1 ? 2 : 20); ++pair) {
      // Start apart by up to half a minor semi-axis along a random normal, tilted.
      Case k = make_case(rng, shape, Orientation::random, -0.5 * unit(rng));
      const Vec3 approach = -k.normal.cast<double>();  // body 2 towards body 1
      ShapedContactMemory memory;
      ContactSolverStats stats;
      GrainPoses poses;
      bool swapped = false;
      for (int s = 0; s < 400; ++s) {
        // Speeds of up to 2e-3 c and 2e-3 rad per step, towards each other in the first half.
        const double speed = 2e-3 * k.c_min * unit(rng);
        k.e2.centre += (s < 200 ? 1.0 : -1.0) * speed * approach + random_unit(rng) * 0.2 * speed;
        k.e1.orientation =
            (Eigen::AngleAxisd(2e-3 * unit(rng), random_unit(rng)) * k.e1.orientation).normalized();
        k.e2.orientation =
            (Eigen::AngleAxisd(2e-3 * unit(rng), random_unit(rng)) * k.e2.orientation).normalized();
        ParticleStore p = store_of(k.e1, k.e2);
        if (s % 97 == 96) swapped = !swapped;  // a rebuild reorders the grains now and then
        if (swapped) p.permute({1, 0});
        poses.update(p);
        const std::size_t i = swapped ? 1 : 0, j = swapped ? 0 : 1;
        const long still_before = stats.still_apart;
        std::vector<ShapedPair> batch(1);
        batch[0].i = i;
        batch[0].j = j;
        batch[0].memory = &memory;
        shaped_pair_geometries(poses, batch, {}, stats);
        const bool touching = batch[0].touching;
        ContactSolverStats reference_stats;
        const ContactGeometry truth = ellipsoid_contact(k.e1, k.e2, reference_stats);
        ASSERT_EQ(touching, truth.touching) << shape.name << " pair " << pair << " step " << s;
        if (touching) {
          EXPECT_NEAR(batch[0].overlap, truth.depth, 1e-13 * k.c_min);
          ++touching_steps;
        }
        skipped += stats.still_apart - still_before;
        ++steps;
      }
    }
  }
  std::printf("%ld steps, %ld touching, %ld skipped by the budget\n", steps, touching_steps, skipped);
  EXPECT_GT(touching_steps, steps / 10);
  EXPECT_GT(skipped, steps / 10);
}

// Two pairs at once (posed_contacts_two, the force loops' batches): the same results bit for bit
// and the same counts as each pair alone, whether both take the straight-line path in one step,
// one needs more steps (a larger move), one is apart, or one overlaps beyond the certificate.
TEST(ForceLoopGeometry, TwoPairsAtOnceAreBitwiseOnePairAtATime) {
  std::mt19937_64 rng(24);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int both_in_lanes = 0;
  for (int trial = 0; trial < 600 / kScale; ++trial) {
    GrainPoses poses[2];
    Vec3 previous[2];
    for (int pair = 0; pair < 2; ++pair) {
      const Shape& shape = kShapes[(trial + pair) % 3];
      const int kind = static_cast<int>(unit(rng) * 8.0);  // 0-4 one step, 5 apart, 6 moved, 7 deep
      Case k = make_case(rng, shape, Orientation::random, kind == 5 ? -1e-3 : kind == 7 ? 0.6 : 1e-3);
      Ellipsoid b1 = k.e1, b2 = k.e2;
      const double move = kind == 6 ? 1e-3 : 1e-8;
      nudge(rng, b1, move * k.c_min, move);
      nudge(rng, b2, move * k.c_min, move);
      ContactSolverStats ignored;
      previous[pair] = ellipsoid_contact(b1, b2, ignored).normal;
      poses[pair].update(store_of(k.e1, k.e2));
    }
    ContactSolverStats alone_stats, two_stats;
    PairContact alone[2], two[2];
    bool alone_touching[2], two_touching[2];
    for (int pair = 0; pair < 2; ++pair)
      alone_touching[pair] =
          posed_contact(poses[pair][0], poses[pair][1], &previous[pair], false, {}, alone_stats, alone[pair]);
    WarmPairSolve lanes[2] = {{&poses[0][0], &poses[0][1], previous[0], {}, false},
                              {&poses[1][0], &poses[1][1], previous[1], {}, false}};
    posed_contacts_two(lanes[0], lanes[1], {}, two_stats);
    for (int pair = 0; pair < 2; ++pair) {
      two[pair] = lanes[pair].out;
      two_touching[pair] = lanes[pair].touching;
    }
    for (int pair = 0; pair < 2; ++pair) {
      SCOPED_TRACE("trial " + std::to_string(trial) + " pair " + std::to_string(pair));
      ASSERT_EQ(two_touching[pair], alone_touching[pair]);
      EXPECT_EQ(two[pair].depth, alone[pair].depth);
      EXPECT_EQ(two[pair].normal, alone[pair].normal);
      if (alone_touching[pair]) {
        EXPECT_EQ(two[pair].lever1, alone[pair].lever1);
        EXPECT_EQ(two[pair].lever2, alone[pair].lever2);
      }
    }
    EXPECT_EQ(two_stats.calls, alone_stats.calls);
    EXPECT_EQ(two_stats.warm_starts, alone_stats.warm_starts);
    EXPECT_EQ(two_stats.newton_iterations, alone_stats.newton_iterations);
    EXPECT_EQ(two_stats.proven_apart, alone_stats.proven_apart);
    EXPECT_EQ(two_stats.fallbacks, alone_stats.fallbacks);
    EXPECT_EQ(two_stats.warm_rejected, alone_stats.warm_rejected);
    EXPECT_EQ(two_stats.uncertified, alone_stats.uncertified);
    EXPECT_EQ(two_stats.failures, alone_stats.failures);
    both_in_lanes +=
        alone_stats.newton_iterations == 2 && alone_stats.calls == 2 && alone_stats.fallbacks == 0;
  }
  EXPECT_GT(both_in_lanes, 100 / kScale);  // the two-lane path itself was exercised
}

}  // namespace
}  // namespace upgrain::dem
