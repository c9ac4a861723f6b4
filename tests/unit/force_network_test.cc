// The force network across the faces of a periodic cell (dem/io/force_network.h,
// docs/output.md "Force network", docs/periodic.md): a pair of touching grains across a face, a
// corner and the sliding face of a sheared cell gives the normal, overlap and branch of the same
// pair inside the cell, and its line is drawn next to a, not across the cell.
#include <gtest/gtest.h>

#include "../common/periodic_pairs.h"
#include "dem/io/force_network.h"

namespace upgrain::dem::io {
namespace {

struct Pair {
  ParticleStore p;
  ContactRecord record;
};

// Grains 0 (at xa) and 1 (at xb): spheres of radius r, or ellipsoids that hold those spheres
// (smallest semi-axis r, so they touch too); and their contact record.
Pair make_pair(const Vec3& xa, const Vec3& xb, bool ellipsoids) {
  Pair out;
  const double r = 1.5e-3;
  if (ellipsoids) {
    const Eigen::Quaterniond qa(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
    const Eigen::Quaterniond qb(Eigen::AngleAxisd(1.1, Vec3(-2, 1, 1).normalized()));
    out.p.add_ellipsoid(0, {Vec3(1.3 * r, 1.15 * r, r), 2650, qa}, {xa, Vec3::Zero(), Vec3::Zero()});
    out.p.add_ellipsoid(1, {Vec3(1.25 * r, 1.1 * r, r), 2650, qb}, {xb, Vec3::Zero(), Vec3::Zero()});
  } else {
    out.p.add_sphere(0, r, 2650, xa, Vec3::Zero(), Vec3::Zero());
    out.p.add_sphere(1, r, 2650, xb, Vec3::Zero(), Vec3::Zero());
  }
  out.record = {0, 1, {}, {}};
  put(out.record.point, xa);
  put(out.record.force, Vec3(-2e-3, 1e-4, 3e-4));
  return out;
}

TEST(ForceNetwork, PairAcrossAFaceACornerAndASlidingFaceIsThePairInsideTheCell) {
  for (const test::PeriodicPair& c : test::periodic_pairs()) {
    for (const bool ellipsoids : {false, true}) {
      SCOPED_TRACE(c.name + (ellipsoids ? ", ellipsoids" : ", spheres"));
      const Pair across = make_pair(c.xa, c.xb, ellipsoids);
      const Pair inside = make_pair(c.inside_a, c.inside_a + c.d, ellipsoids);
      const NetworkContact a = force_network(across.p, {}, {across.record}, c.cell).at(0);
      const NetworkContact i = force_network(inside.p, {}, {inside.record}, c.cell).at(0);
      // The pair inside: the centres' branch as it is, nothing shifted.
      EXPECT_EQ(i.branch, c.d);
      EXPECT_TRUE(i.shift.isZero(0.0));
      ASSERT_GT(i.overlap, 1e-5);
      // Across: the same branch bits (exact on the grid); the normal and overlap of the same
      // geometry, bitwise for spheres, to the solver's round-off for ellipsoids.
      EXPECT_EQ(a.branch, c.d);
      EXPECT_FALSE(a.shift.isZero(0.0));
      EXPECT_EQ(a.shift, a.branch - (c.xb - c.xa));
      const double tol = ellipsoids ? 1e-12 : 0.0;
      EXPECT_LE((a.normal - i.normal).norm(), tol);
      EXPECT_LE(std::abs(a.overlap - i.overlap), tol * 1.5e-3);
      EXPECT_LE((a.normal_force + a.tangential_force - get(across.record.force)).norm(), 1e-18);

      // The line from a to b's image next to it: a node more, within a diameter of the cell.
      const LineNodes l = line_nodes(across.p, {a});
      ASSERT_EQ(l.position.size(), 3u);
      EXPECT_EQ(l.nodes, (std::vector<std::int64_t>{0, 2}));
      EXPECT_EQ(l.position[2] - l.position[0], c.d);
      for (const Vec3& x : l.position)
        for (int d = 0; d < 3; ++d) {
          EXPECT_GE(x[d], c.cell.box.lo[d] - 3e-3);
          EXPECT_LE(x[d], c.cell.box.hi[d] + 3e-3);
        }
      const LineNodes li = line_nodes(inside.p, {i});
      EXPECT_EQ(li.position.size(), 2u);
      EXPECT_EQ(li.nodes, (std::vector<std::int64_t>{0, 1}));
    }
  }
}

// A bounded box: the branch is x_b - x_a and the lines are the grains and the ids, whatever the
// distance (as before the cell was passed).
TEST(ForceNetwork, BoundedBoxKeepsTheCentresBranchAndLines) {
  const Vec3 xa(0.0195, 0.01, 0.01), xb(0.0005, 0.01, 0.01);
  const Pair far = make_pair(xa, xb, false);
  const NetworkContact c = force_network(far.p, {}, {far.record}, PeriodicCell{}).at(0);
  EXPECT_EQ(c.branch, xb - xa);
  EXPECT_TRUE(c.shift.isZero(0.0));
  EXPECT_LT(c.overlap, 0.0);
  const LineNodes l = line_nodes(far.p, {c});
  EXPECT_EQ(l.position, far.p.x);
  EXPECT_EQ(l.nodes, (std::vector<std::int64_t>{0, 1}));
}

}  // namespace
}  // namespace upgrain::dem::io
