// Finite strain per grid cell (upscale/strain/grid_strain.h): an affine motion of a random
// packing over a grid is recovered in every valid cell by both definitions, for Lagrangian
// and Eulerian sets; sparse, flat and inverted cells are reported with their reason and no
// NaN; a rigid rotation of the whole packing gives E = e = 0, D = 0, W = the spin, R = Q;
// the increment from the previous evaluation composes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "dem/core/error.h"
#include "upscale/strain/deformation_fit.h"
#include "upscale/strain/grid_strain.h"
#include "upscale/strain/strain_measures.h"

using namespace upgrain::dem;
using namespace upgrain::upscale;

namespace {

constexpr StrainDefinition kBoth[] = {StrainDefinition::best_fit, StrainDefinition::tessellation};

// A packing over a 3 x 3 x 2 grid 2 m from the origin: about 30 random points per cell,
// except cells 0, 5, 10, 15 (0, 1, 2, 3 points) and cell 7 (6 points on one plane).
struct Packing {
  RegularGrid grid;
  std::vector<GlobalId> id;
  std::vector<Vec3> x;
  std::vector<int> sparse_cells = {0, 5, 10, 15};
  int flat_cell = 7;
};

Packing make_packing(unsigned seed) {
  Packing p;
  p.grid.lo = Vec3(1.2, 1.1, 0.9);
  p.grid.hi = p.grid.lo + Vec3(0.06, 0.06, 0.04);
  p.grid.n[0] = 3;
  p.grid.n[1] = 3;
  p.grid.n[2] = 2;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  const Vec3 h = (p.grid.hi - p.grid.lo).cwiseQuotient(Vec3(3, 3, 2));
  GlobalId next = 1000;
  for (int c = 0; c < p.grid.num_cells(); ++c) {
    const Vec3 corner = p.grid.cell_centre(c) - 0.5 * h;
    const auto sparse = std::find(p.sparse_cells.begin(), p.sparse_cells.end(), c);
    const int n = sparse != p.sparse_cells.end() ? static_cast<int>(sparse - p.sparse_cells.begin()) : 30;
    const int count = c == p.flat_cell ? 6 : n;
    for (int k = 0; k < count; ++k) {
      Vec3 s(u(rng), u(rng), u(rng));
      if (c == p.flat_cell) s.z() = 0.5;
      p.x.push_back(corner + s.cwiseProduct(h));
      p.id.push_back(next);
      next += 3;  // ids need not be contiguous
    }
  }
  return p;
}

Mat3 rotation(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).matrix(); }

// The current state under x = F X + c, v = L x + v0, stored in a shuffled order.
struct State {
  std::vector<GlobalId> id;
  std::vector<Vec3> x, v;
  [[nodiscard]] ParticleKinematics view() const { return {id, x, v}; }
};

State move(const Packing& p, const Mat3& f, const Vec3& c, const Mat3& l, const Vec3& v0, unsigned seed) {
  std::vector<std::size_t> order(p.id.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
  State s;
  for (std::size_t k : order) {
    s.id.push_back(p.id[k]);
    s.x.push_back(f * p.x[k] + c);
    s.v.push_back(l * s.x.back() + v0);
  }
  return s;
}

bool all_finite(const GridStrain& g) {
  for (int d = 0; d < kStrainDefinitionCount; ++d) {
    const CellStrainFields& f = g.fields[d];
    for (const auto* m : {&f.deformation_gradient, &f.velocity_gradient, &f.increment, &f.green_lagrange,
                          &f.euler_almansi, &f.hencky, &f.rotation, &f.rate_of_deformation, &f.spin})
      for (const Mat3& t : *m)
        if (!t.allFinite()) return false;
    for (const auto* s : {&f.jacobian, &f.log_jacobian, &f.equivalent_shear_strain, &f.equivalent_shear_rate,
                          &f.increment_log_jacobian, &f.increment_equivalent_shear_strain, &f.residual_rms})
      for (double v : *s)
        if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

TEST(GridStrain, AffineMotionOfARandomPackingIsRecoveredInEveryValidCellBothWays) {
  const Packing p = make_packing(7);
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.5, 100);
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 1.0;
  const Mat3 f = rotation(Vec3(1, -2, 0.5), 2.0) * shear * Vec3(1.5, 1.0, 0.8).asDiagonal();
  Mat3 l;
  l << 0.3, -1.2, 0.5, 0.7, -0.2, 0.1, -0.4, 0.9, 0.6;
  const State s = move(p, f, Vec3(0.3, -0.2, 0.1), l, Vec3(0.01, 0.02, -0.03), 3);
  double worst_f = 0.0, worst_l = 0.0;
  for (StrainSet set : {StrainSet::lagrangian, StrainSet::eulerian}) {
    GridStrainOptions o;
    o.set = set;
    // Eulerian: a current grid over the moved packing's box, so its cells hold other sets.
    RegularGrid now = p.grid;
    if (set == StrainSet::eulerian) {
      now.lo = now.hi = s.x[0];
      for (const Vec3& x : s.x) {
        now.lo = now.lo.cwiseMin(x);
        now.hi = now.hi.cwiseMax(x);
      }
      now.hi += Vec3::Constant(1e-9);
    }
    const GridStrain g = grid_strain(ref, now, s.view(), {1.5, 200}, o);
    EXPECT_EQ(g.set, set);
    EXPECT_EQ(g.reference_time, 0.5);
    EXPECT_EQ(g.untracked, 0);
    ASSERT_TRUE(all_finite(g));
    long total = 0;
    for (long n : g.particles) total += n;
    EXPECT_EQ(total, static_cast<long>(p.id.size()));
    for (StrainDefinition d : kBoth) {
      const CellStrainFields& r = g[d];
      int valid = 0;
      for (int c = 0; c < g.grid.num_cells(); ++c) {
        if (g.particles[c] < kMinFitPoints) {
          EXPECT_EQ(r.f_reason[c], StrainReason::too_few_particles) << c;
          EXPECT_EQ(r.l_reason[c], StrainReason::too_few_particles) << c;
          EXPECT_EQ(r.increment_reason[c], StrainReason::too_few_particles) << c;
          EXPECT_EQ(r.deformation_gradient[c], Mat3::Zero());
          EXPECT_EQ(r.jacobian[c], 0.0);
          continue;
        }
        if (set == StrainSet::lagrangian && c == p.flat_cell) {
          EXPECT_EQ(r.f_reason[c], StrainReason::degenerate_set);
          EXPECT_EQ(r.l_reason[c], StrainReason::degenerate_set);  // still flat now
          continue;
        }
        if (r.f_reason[c] != StrainReason::valid) continue;  // Eulerian sets can straddle
        ++valid;
        worst_f = std::max(worst_f, (r.deformation_gradient[c] - f).norm() / f.norm());
        EXPECT_LE((r.deformation_gradient[c] - f).norm(), 1e-12 * f.norm()) << name_of(d) << " cell " << c;
        EXPECT_NEAR(r.jacobian[c], f.determinant(), 1e-12);
        EXPECT_NEAR(r.log_jacobian[c], std::log(f.determinant()), 1e-12);
        const StrainMeasures m = strain_measures(f);
        EXPECT_LE((r.green_lagrange[c] - m.green_lagrange).norm(), 1e-11);
        EXPECT_LE((r.hencky[c] - m.hencky_left).norm(), 1e-11);
        EXPECT_LE((r.increment[c] - f).norm(), 1e-12 * f.norm());  // no previous: F_inc = F
        ASSERT_EQ(r.l_reason[c], StrainReason::valid);
        worst_l = std::max(worst_l, (r.velocity_gradient[c] - l).norm() / l.norm());
        EXPECT_LE((r.velocity_gradient[c] - l).norm(), 1e-12 * l.norm()) << name_of(d) << " cell " << c;
        EXPECT_LE((r.rate_of_deformation[c] + r.spin[c] - l).norm(), 1e-12 * l.norm());
      }
      EXPECT_GE(valid, set == StrainSet::lagrangian ? 13 : 8) << name_of(d);
    }
  }
  char text[64];
  std::snprintf(text, sizeof text, "%.2e", worst_f);
  RecordProperty("worst_relative_F_error", text);
  std::snprintf(text, sizeof text, "%.2e", worst_l);
  RecordProperty("worst_relative_L_error", text);
}

TEST(GridStrain, RigidRotationOfTheWholePackingHasNoStrainAndTheSpin) {
  const Packing p = make_packing(11);
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  const Vec3 w(3.0, -1.0, 2.0);
  const double pi = std::numbers::pi;
  for (const Mat3& q : {rotation(Vec3::UnitZ(), pi / 2), rotation(Vec3(1, 1, 1), pi), rotation(w, 1.0)}) {
    const State s = move(p, q, Vec3(-0.4, 0.2, 0.3), cross_matrix(w), Vec3(0.1, 0.2, -0.3), 5);
    const GridStrain g = grid_strain(ref, p.grid, s.view(), {1.0, 10}, {});
    ASSERT_TRUE(all_finite(g));
    for (StrainDefinition d : kBoth) {
      const CellStrainFields& r = g[d];
      int valid = 0;
      for (int c = 0; c < g.grid.num_cells(); ++c) {
        if (r.f_reason[c] != StrainReason::valid) continue;
        ++valid;
        EXPECT_LE((r.deformation_gradient[c] - q).norm(), 1e-12);
        EXPECT_LE((r.rotation[c] - q).norm(), 1e-12);
        EXPECT_LE(r.green_lagrange[c].norm(), 1e-12);
        EXPECT_LE(r.euler_almansi[c].norm(), 1e-12);
        EXPECT_LE(r.hencky[c].norm(), 1e-12);
        EXPECT_LE(std::abs(r.log_jacobian[c]), 1e-12);
        EXPECT_LE(r.equivalent_shear_strain[c], 1e-12);
        ASSERT_EQ(r.l_reason[c], StrainReason::valid);
        EXPECT_LE(r.rate_of_deformation[c].norm(), 1e-12 * w.norm());
        EXPECT_LE((r.spin[c] - cross_matrix(w)).norm(), 1e-12 * w.norm());
        EXPECT_LE(r.equivalent_shear_rate[c], 1e-12 * w.norm());
      }
      EXPECT_EQ(valid, 13) << name_of(d);
    }
  }
}

TEST(GridStrain, IncrementFromThePreviousEvaluationComposes) {
  const Packing p = make_packing(13);
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  Mat3 shear = Mat3::Identity();
  shear(0, 2) = 0.4;
  const Mat3 f1 = rotation(Vec3(0, 1, 1), 0.7) * Vec3(1.2, 0.9, 1.0).asDiagonal();
  const Mat3 g2 = shear * rotation(Vec3(1, 0, 0), -0.3);
  const State s1 = move(p, f1, Vec3(0.1, 0, 0), Mat3::Zero(), Vec3::Zero(), 1);
  const State s2 = move(p, g2 * f1, Vec3(0, 0.1, 0), Mat3::Zero(), Vec3::Zero(), 2);
  const GridStrain e1 = grid_strain(ref, p.grid, s1.view(), {1.0, 1}, {});
  const GridStrain e2 = grid_strain(ref, p.grid, s2.view(), {2.0, 2}, {}, &e1);
  ASSERT_TRUE(all_finite(e2));
  for (StrainDefinition d : kBoth) {
    for (int c = 0; c < p.grid.num_cells(); ++c) {
      if (e2[d].f_reason[c] != StrainReason::valid) {
        EXPECT_EQ(e2[d].increment_reason[c], e2[d].f_reason[c]);
        continue;
      }
      ASSERT_EQ(e2[d].increment_reason[c], StrainReason::valid);
      EXPECT_LE((e2[d].increment[c] - g2).norm(), 1e-12);
      EXPECT_NEAR(e2[d].increment_log_jacobian[c], 0.0, 1e-12);
    }
  }
}

TEST(GridStrain, InvertedMissingAndNonFiniteAreReportedNotNaN) {
  const Packing p = make_packing(17);
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  // A reflection: every populated cell has J = -1.
  State s = move(p, Vec3(-1.0, 1.0, 1.0).asDiagonal(), Vec3::Zero(), Mat3::Zero(), Vec3::Zero(), 1);
  GridStrain g = grid_strain(ref, p.grid, s.view(), {1.0, 1}, {});
  ASSERT_TRUE(all_finite(g));
  for (StrainDefinition d : kBoth)
    for (int c = 0; c < p.grid.num_cells(); ++c)
      if (g.particles[c] >= 30) {
        EXPECT_EQ(g[d].f_reason[c], StrainReason::non_positive_jacobian) << name_of(d) << " " << c;
        EXPECT_EQ(g[d].l_reason[c], StrainReason::valid);  // L = 0 is a valid gradient
        EXPECT_EQ(g[d].deformation_gradient[c], Mat3::Zero());
      }
  // A particle lost, one at NaN: the NaN cell is reported, the loss counted.
  s = move(p, Mat3::Identity(), Vec3::Zero(), Mat3::Zero(), Vec3::Zero(), 2);
  const GlobalId nan_id = p.id[p.id.size() - 1];
  const GlobalId lost_id = p.id[p.id.size() - 2];
  for (std::size_t i = 0; i < s.id.size(); ++i)
    if (s.id[i] == nan_id) s.x[i].x() = std::nan("");
  for (std::size_t i = 0; i < s.id.size(); ++i)
    if (s.id[i] == lost_id) {
      s.id.erase(s.id.begin() + static_cast<long>(i));
      s.x.erase(s.x.begin() + static_cast<long>(i));
      s.v.erase(s.v.begin() + static_cast<long>(i));
      break;
    }
  g = grid_strain(ref, p.grid, s.view(), {1.0, 1}, {});
  ASSERT_TRUE(all_finite(g));
  EXPECT_EQ(g.untracked, 1);
  const int last = p.grid.num_cells() - 1;
  for (StrainDefinition d : kBoth) {
    EXPECT_EQ(g[d].f_reason[last], StrainReason::non_finite) << name_of(d);
    EXPECT_EQ(g[d].l_reason[last], StrainReason::non_finite) << name_of(d);
  }
  // Repeated ids are refused.
  std::vector<GlobalId> twice = p.id;
  twice[1] = twice[0];
  EXPECT_THROW(make_strain_reference(twice, p.x, p.grid, 0.0, 0), upgrain::Error);
}

// The reference tessellation of a cell is kept while its set is the same (grid_strain.h,
// CellTessellation): F is then bitwise the F of a fresh tessellation, and a cell whose set
// changed (a particle lost), or an evaluation from another reference, tessellates anew.
TEST(GridStrain, ReferenceTessellationIsReusedWhileTheSetIsTheSame) {
  const Packing p = make_packing(11);
  const StrainReference ref = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  // Non-affine motions, so that F depends on the tessellation.
  auto wobble = [&](double a, unsigned seed) {
    State s = move(p, Mat3::Identity(), Vec3::Zero(), Mat3::Zero(), Vec3::Zero(), seed);
    for (Vec3& x : s.x) x += a * Vec3(std::sin(90 * x.y()), std::cos(70 * x.z()), std::sin(80 * x.x()));
    return s;
  };
  GridStrainOptions o;
  o.definitions = {false, true};
  const int tess = static_cast<int>(StrainDefinition::tessellation);
  const GridStrain g1 = grid_strain(ref, p.grid, wobble(1e-3, 1).view(), {1.0, 1}, o);
  const State s2 = wobble(2e-3, 2);
  const GridStrain g2 = grid_strain(ref, p.grid, s2.view(), {2.0, 2}, o, &g1);
  const GridStrain fresh = grid_strain(ref, p.grid, s2.view(), {2.0, 2}, o);
  int reused = 0, differs = 0;
  for (int c = 0; c < p.grid.num_cells(); ++c) {
    if (g1.particles[c] < kMinFitPoints) {
      EXPECT_EQ(g2.reference_tessellations[c], nullptr);
      continue;
    }
    EXPECT_EQ(g2.reference_tessellations[c].get(), g1.reference_tessellations[c].get()) << c;
    EXPECT_NE(fresh.reference_tessellations[c].get(), g1.reference_tessellations[c].get()) << c;
    reused += g2.fields[tess].f_reason[c] == StrainReason::valid;
    EXPECT_EQ(g2.fields[tess].f_reason[c], fresh.fields[tess].f_reason[c]);
    EXPECT_TRUE(g2.fields[tess].deformation_gradient[c] == fresh.fields[tess].deformation_gradient[c]) << c;
    differs += (g2.fields[tess].deformation_gradient[c] - g1.fields[tess].deformation_gradient[c]).norm() > 0;
  }
  EXPECT_GT(reused, 8);
  EXPECT_EQ(differs, reused) << "the motion changed F in every valid cell";

  // One particle (the first of the shuffled store) is lost: its cell tessellates anew, the
  // others reuse.
  State s3 = wobble(3e-3, 3);
  const std::size_t lost = 0;
  int lost_cell = -1;
  for (std::size_t k = 0; k < p.id.size(); ++k)
    if (p.id[k] == s3.id[lost]) lost_cell = p.grid.cell_of(p.x[k]);
  ASSERT_GE(g2.particles[lost_cell], kMinFitPoints + 1);
  s3.id.erase(s3.id.begin() + static_cast<long>(lost));
  s3.x.erase(s3.x.begin() + static_cast<long>(lost));
  s3.v.erase(s3.v.begin() + static_cast<long>(lost));
  const GridStrain g3 = grid_strain(ref, p.grid, s3.view(), {3.0, 3}, o, &g2);
  const GridStrain fresh3 = grid_strain(ref, p.grid, s3.view(), {3.0, 3}, o);
  EXPECT_EQ(g3.untracked, 1);
  for (int c = 0; c < p.grid.num_cells(); ++c) {
    if (g3.particles[c] < kMinFitPoints) continue;
    if (c == lost_cell) {
      EXPECT_NE(g3.reference_tessellations[c].get(), g2.reference_tessellations[c].get());
    } else {
      EXPECT_EQ(g3.reference_tessellations[c].get(), g2.reference_tessellations[c].get()) << c;
    }
    EXPECT_TRUE(g3.fields[tess].deformation_gradient[c] == fresh3.fields[tess].deformation_gradient[c]) << c;
  }
  // Another reference: nothing is reused.
  const StrainReference other = make_strain_reference(p.id, p.x, p.grid, 0.5, 50);
  const GridStrain g4 = grid_strain(other, p.grid, s2.view(), {4.0, 4}, o, &g2);
  for (int c = 0; c < p.grid.num_cells(); ++c) {
    if (g4.reference_tessellations[c]) {
      EXPECT_NE(g4.reference_tessellations[c].get(), g2.reference_tessellations[c].get()) << c;
    }
  }
}

// Cells that are not those of a grid (the MPI blocks of an MPI run): a partition given per
// particle. With the grid's own cells it is grid_strain() bit for bit; with two "blocks"
// (the packing split at x = 1.23, as a rank boundary) each block's F and L are the affine map's,
// Lagrangian sets follow the blocks of t0 and Eulerian ones those of now; a cell index out of
// range is refused.
TEST(GridStrain, PartitionByBlocksIsTheSameComputation) {
  const Packing p = make_packing(11);
  Mat3 shear = Mat3::Identity();
  shear(0, 2) = 0.4;
  const Mat3 f = rotation(Vec3(0.2, 1, -0.3), 0.7) * shear;
  Mat3 l;
  l << 0.1, 0.4, -0.2, -0.3, 0.2, 0.5, 0.6, -0.1, -0.3;
  const State s = move(p, f, Vec3(-0.1, 0.05, 0.2), l, Vec3::Zero(), 9);
  // The grid's cells given per particle: the same result.
  std::vector<int> cell(p.x.size());
  for (std::size_t k = 0; k < p.x.size(); ++k) cell[k] = p.grid.cell_of(p.x[k]);
  const StrainReference by_grid = make_strain_reference(p.id, p.x, p.grid, 0.0, 0);
  const StrainReference by_cells = make_strain_reference(p.id, p.x, cell, p.grid.num_cells(), 0.0, 0);
  const GridStrain a = grid_strain(by_grid, p.grid, s.view(), {1.0, 10}, {});
  const GridStrain b = partition_strain(by_cells, {}, s.view(), {1.0, 10}, {});
  for (StrainDefinition d : kBoth)
    for (int c = 0; c < p.grid.num_cells(); ++c) {
      EXPECT_EQ(a[d].deformation_gradient[c], b[d].deformation_gradient[c]);
      EXPECT_EQ(a[d].velocity_gradient[c], b[d].velocity_gradient[c]);
      EXPECT_EQ(a[d].f_reason[c], b[d].f_reason[c]);
    }
  // Two blocks split at x = 1.23 at t0; now the split of the moved packing at its median x.
  std::vector<int> block_then(p.x.size());
  for (std::size_t k = 0; k < p.x.size(); ++k) block_then[k] = p.x[k].x() < 1.23 ? 0 : 1;
  std::vector<double> xs;
  for (const Vec3& x : s.x) xs.push_back(x.x());
  std::nth_element(xs.begin(), xs.begin() + static_cast<long>(xs.size() / 2), xs.end());
  const double median = xs[xs.size() / 2];
  std::vector<int> block_now(s.x.size());
  for (std::size_t k = 0; k < s.x.size(); ++k) block_now[k] = s.x[k].x() < median ? 0 : 1;
  const StrainReference blocks = make_strain_reference(p.id, p.x, block_then, 2, 0.0, 0);
  for (StrainSet set : {StrainSet::lagrangian, StrainSet::eulerian}) {
    GridStrainOptions o;
    o.set = set;
    const GridStrain g = partition_strain(blocks, block_now, s.view(), {1.0, 10}, o);
    ASSERT_EQ(g.particles.size(), 2u);
    EXPECT_EQ(g.particles[0] + g.particles[1], static_cast<long>(p.id.size()));
    if (set == StrainSet::eulerian) {
      EXPECT_LE(std::abs(g.particles[0] - g.particles[1]), 1);
    }
    for (StrainDefinition d : kBoth)
      for (int c = 0; c < 2; ++c) {
        ASSERT_EQ(g[d].f_reason[c], StrainReason::valid) << name_of(d) << " block " << c;
        EXPECT_LE((g[d].deformation_gradient[c] - f).norm(), 1e-12 * f.norm());
        EXPECT_LE((g[d].velocity_gradient[c] - l).norm(), 1e-12 * l.norm());
      }
  }
  const std::vector<int> bad(p.x.size(), 2);
  EXPECT_THROW(make_strain_reference(p.id, p.x, bad, 2, 0.0, 0), upgrain::Error);
  GridStrainOptions eulerian;
  eulerian.set = StrainSet::eulerian;
  EXPECT_THROW(partition_strain(blocks, bad, s.view(), {1.0, 10}, eulerian), upgrain::Error);
}
