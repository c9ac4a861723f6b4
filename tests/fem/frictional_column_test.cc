// The frictional column (fem/frictional_column.h) against independent answers: the exact
// confined column without friction, Janssen's slab solution where the walls slip
// everywhere, Rankine's active state under a lateral relaxation, invariants of the
// continuum problem (the slip traction does not depend on the penalty; a cohesionless
// answer does not depend on the load steps), Newton's order of convergence, and 1 against
// 2 ranks. Every test runs on all ranks of MPI_COMM_WORLD: CTest runs this binary plain and
// under `mpiexec -n 2`. EXPECT_* only around collective calls, as in elastic_column_test.cc.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

#include "../common/world.h"
#include "fem/analytic/confined_column.h"
#include "fem/analytic/earth_pressure.h"
#include "fem/analytic/janssen.h"
#include "fem/frictional_column.h"

namespace upgrain::fem {
namespace {

using test::world_rank;
using test::world_size;

constexpr double degree = std::numbers::pi / 180.0;

// A tall silo: a 2 cm square box filled 6 cm high (H = 3D), so that Janssen's effect is
// large: with mu_w = 0.2 and K = 0.43 the floor carries 62 % of the weight. Elastic,
// E = 50 MPa, nu = 0.3; coarse mesh 2 x 2 x 6, Q2.
FrictionalColumnProblem silo(double wall_friction, unsigned refinements) {
  FrictionalColumnProblem p;
  p.column.length_x = p.column.length_y = 0.02;
  p.column.height = 0.06;
  p.column.density = 1600.0;
  p.column.youngs_modulus = 5e7;
  p.column.poisson_ratio = 0.3;
  p.column.cells = {2, 2, 6};
  p.column.degree = 2;
  p.column.refinements = refinements;
  p.walls.side = {wall_friction, wall_friction, wall_friction, wall_friction};
  p.loading.load_steps = 1;
  return p;
}

// Mean sigma_zz over each level of coarse cells: the slab mean over that level's height.
std::vector<double> level_means(const FrictionalColumnProblem& p, const FrictionalColumnSolution& s) {
  const ColumnProblem& c = p.column;
  std::vector<double> out(c.cells[2], 0.0);
  for (unsigned k = 0; k < c.cells[2]; ++k) {
    for (unsigned j = 0; j < c.cells[1]; ++j)
      for (unsigned i = 0; i < c.cells[0]; ++i)
        out[k] += s.cell_average_stress[coarse_cell_index(c, i, j, k)][8];
    out[k] /= c.cells[0] * c.cells[1];
  }
  return out;
}

// Janssen for the problem's box with one wall friction mu on all four walls and
// K = nu / (1 - nu), the elastic column's ratio at rest.
JanssenColumn janssen_of(const FrictionalColumnProblem& p) {
  const ColumnProblem& c = p.column;
  const double mu = p.walls.side[0];
  return {c.density * c.gravity, c.length_x * c.length_y, mu * 2.0 * (c.length_x + c.length_y),
          analytic_k0(c.poisson_ratio), c.height};
}

struct JanssenAgreement {
  double largest_difference;  // max over levels of |FEM - Janssen| (Pa)
  double largest_effect;      // max over levels of |hydrostatic - Janssen| (Pa)
};
JanssenAgreement compare_with_janssen(const FrictionalColumnProblem& p, const FrictionalColumnSolution& s) {
  const JanssenColumn j = janssen_of(p);
  const ConfinedColumn hydrostatic{j.unit_weight, p.column.height, 1.0, 0.3};
  const std::vector<double> levels = level_means(p, s);
  const double dz = p.column.height / p.column.cells[2];
  JanssenAgreement a{0.0, 0.0};
  for (unsigned k = 0; k < levels.size(); ++k) {
    const double janssen = j.mean_vertical_stress(k * dz, (k + 1) * dz);
    a.largest_difference = std::max(a.largest_difference, std::abs(levels[k] - janssen));
    a.largest_effect = std::max(a.largest_effect,
                                std::abs(hydrostatic.mean_vertical_stress(k * dz, (k + 1) * dz) - janssen));
  }
  return a;
}

void print_janssen_header() {
  if (world_rank() == 0)
    std::printf(
        "| mu_w | refinements | dofs | Newton its | GMRES its | slipping wall share | max level |FEM - "
        "Janssen| / "
        "max |hydrostatic - Janssen| | wall share FEM | wall share Janssen | (floor + walls - W)/W | solve "
        "(s) "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|\n");
}
void print_janssen_row(const FrictionalColumnProblem& p, const FrictionalColumnSolution& s,
                       const JanssenAgreement& a) {
  if (world_rank() != 0) return;
  std::printf("| %.2f | %u | %lu | %u | %u | %.4f | %.4f | %.5f | %.5f | %.1e | %.2f |\n", p.walls.side[0],
              p.column.refinements, static_cast<unsigned long>(s.n_dofs), s.newton_iterations,
              s.linear_iterations, s.slipping_wall_share, a.largest_difference / a.largest_effect,
              s.side_wall_vertical_force / s.weight, janssen_of(p).wall_share(),
              (s.floor_vertical_force + s.side_wall_vertical_force - s.weight) / s.weight, s.total_seconds);
}

// The largest difference between two solutions' coarse-cell averages, over every cell and
// component, relative to rho g H; printed by rank 0 with what is compared.
double largest_difference(const FrictionalColumnProblem& p, const FrictionalColumnSolution& a,
                          const FrictionalColumnSolution& b, const char* what) {
  if (a.cell_average_stress.size() != b.cell_average_stress.size()) return INFINITY;
  double largest = 0.0;
  for (std::size_t c = 0; c < a.cell_average_stress.size(); ++c)
    for (int e = 0; e < 9; ++e)
      largest = std::max(largest, std::abs(a.cell_average_stress[c][e] - b.cell_average_stress[c][e]));
  largest /= p.column.density * p.column.gravity * p.column.height;
  if (world_rank() == 0)
    std::printf("  %s: largest difference of the cell averages %.2e rho g H\n", what, largest);
  return largest;
}

// Without friction the walls are rollers: the answer is the exact confined column, loaded
// at once or built layer by layer (linear elasticity on rollers: the layers' stresses
// superpose to the same field), elastic or Drucker–Prager whose cone contains the at-rest
// state (K0 = 0.43 > K_a = 1/3 for phi = 30 degrees, outer cone).
TEST(FrictionalColumn, WithoutFrictionItIsTheConfinedColumn) {
  const std::filesystem::path folder =
      std::filesystem::current_path() / ("fem_frictional_output_np" + std::to_string(world_size()));
  for (const bool staged : {false, true})
    for (const ColumnMaterial material : {ColumnMaterial::elastic, ColumnMaterial::drucker_prager}) {
      FrictionalColumnProblem p = silo(0.0, 0);
      p.column.cells = {2, 2, 4};
      p.material = material;
      p.loading.staged_construction = staged;
      p.newton.tolerance = 1e-12;
      const bool write = staged && material == ColumnMaterial::drucker_prager;
      const FrictionalColumnSolution s =
          solve_frictional_column(p, MPI_COMM_WORLD, write ? folder.string() : "");
      const ConfinedColumn exact = analytic_solution(p.column);
      const double dz = p.column.height / p.column.cells[2];
      // Largest deviation of any component of any coarse average from the exact one,
      // relative to that cell's exact sigma_zz.
      double deviation = 0.0;
      for (unsigned c = 0; c < s.cell_average_stress.size(); ++c) {
        const auto& sigma = s.cell_average_stress[c];
        const unsigned k = c / (p.column.cells[0] * p.column.cells[1]);
        const double szz = exact.mean_vertical_stress(k * dz, (k + 1) * dz);
        const double expected[9] = {exact.k0() * szz, 0, 0, 0, exact.k0() * szz, 0, 0, 0, szz};
        for (int e = 0; e < 9; ++e)
          deviation = std::max(deviation, std::abs(sigma[e] - expected[e]) / std::abs(szz));
      }
      if (world_rank() == 0)
        std::printf("  staged %d, material %d: largest deviation from the exact column %.2e\n", staged,
                    static_cast<int>(material), deviation);
      SCOPED_TRACE(::testing::Message() << "staged " << staged << " material " << static_cast<int>(material));
      EXPECT_LT(deviation, 1e-10);
      EXPECT_EQ(s.plastic_volume_share, 0.0);
      EXPECT_EQ(s.side_wall_vertical_force, 0.0);
      if (write) {
        EXPECT_TRUE(std::filesystem::is_regular_file(folder / "column.pvtu"));
      }
    }
}

// Janssen's assumptions are full friction everywhere on the walls, a constant K and a
// uniform sigma_v across each slab. With weak friction (small mu_w K) the settling column
// slides down the walls everywhere (a stick zone would need a wall shear below mu p with
// the wall holding the column still, which only the floor's corner can give), K stays near
// the elastic K0 = nu / (1 - nu), and the slab mean obeys Janssen's equilibrium exactly;
// so the FEM must lie close to Janssen and closer as mu_w K shrinks. The figures (docs/fem.md)
// come from DISABLED_JanssenVerificationTable.
TEST(FrictionalColumn, SlippingWallsApproachJanssen) {
  print_janssen_header();
  double previous_ratio = 0.0;
  for (const double mu : {0.2, 0.05}) {
    const FrictionalColumnProblem p = silo(mu, 1);
    const FrictionalColumnSolution s = solve_frictional_column(p, MPI_COMM_WORLD, "");
    const JanssenAgreement a = compare_with_janssen(p, s);
    print_janssen_row(p, s, a);
    EXPECT_EQ(s.slipping_wall_share, 1.0) << "the walls must slip everywhere in this regime";
    // The Janssen effect is large (35 % of the hydrostatic floor stress at mu = 0.2) and the
    // FEM is within 2 % of it (measured 0.9 % at mu = 0.2, 0.3 % at mu = 0.05).
    EXPECT_LT(a.largest_difference, 0.02 * a.largest_effect);
    const JanssenColumn j = janssen_of(p);
    EXPECT_NEAR(s.side_wall_vertical_force / s.weight, j.wall_share(), 0.01 * j.wall_share());
    // Equilibrium of the whole column: floor (from the stress at the floor) and walls carry
    // the weight, up to the discretisation error of the floor stress.
    EXPECT_NEAR(s.floor_vertical_force + s.side_wall_vertical_force, s.weight, 1e-3 * s.weight);
    const double ratio = a.largest_difference / a.largest_effect;
    if (previous_ratio > 0.0) {
      EXPECT_LT(ratio, previous_ratio) << "weaker friction must come closer to Janssen";
    }
    previous_ratio = ratio;
  }
}

// The table of docs/fem.md: refinements 0-2 (the finest takes ~10 s per mu on one core).
//   fem_tests --gtest_also_run_disabled_tests --gtest_filter='*JanssenVerificationTable*'
TEST(FrictionalColumn, DISABLED_JanssenVerificationTable) {
  print_janssen_header();
  for (const double mu : {0.05, 0.1, 0.2, 0.4})
    for (unsigned refinements = 0; refinements <= 2; ++refinements) {
      const FrictionalColumnProblem p = silo(mu, refinements);
      const FrictionalColumnSolution s = solve_frictional_column(p, MPI_COMM_WORLD, "");
      print_janssen_row(p, s, compare_with_janssen(p, s));
    }
}

// Where the walls slip, the traction is mu p whatever the tangential penalty: a penalty ten
// times stiffer gives the same answer to the Newton tolerance.
TEST(FrictionalColumn, SlipAnswerDoesNotDependOnThePenalty) {
  FrictionalColumnProblem p = silo(0.2, 0);
  p.newton.tolerance = 1e-12;
  const FrictionalColumnSolution soft = solve_frictional_column(p, MPI_COMM_WORLD, "");
  p.walls.penalty_factor *= 10.0;
  const FrictionalColumnSolution stiff = solve_frictional_column(p, MPI_COMM_WORLD, "");
  EXPECT_EQ(soft.slipping_wall_share, 1.0);
  EXPECT_EQ(stiff.slipping_wall_share, 1.0);
  EXPECT_LT(largest_difference(p, soft, stiff, "penalty x10"), 1e-9);
}

// Rankine's active state. Gravity first (the at-rest K0 = 0.43 lies inside the cone), then
// the walls x = Lx and y = Ly move outwards. All walls are frictionless, so every point
// keeps sigma_xx = sigma_yy (triaxial compression, the Mohr–Coulomb corner the outer cone
// passes through) while sigma_zz stays the overburden. The lateral stress falls until the
// point yields, which on that corner is sigma_h = K_a sigma_v - 2 c sqrt(K_a) (compression
// positive), K_a = (1 - sin phi) / (1 + sin phi), whatever the flow rule; it stays there as
// the walls move on. The relaxation needed is the elastic one, for the deepest point:
// d sigma_h = E / (1 - nu) d eps_h with sigma_zz fixed; the walls move twice that.
TEST(FrictionalColumn, LateralRelaxationReachesRankineActiveState) {
  struct Case {
    double psi_deg, cohesion;
  };
  for (const Case& m : {Case{30.0, 0.0}, Case{0.0, 0.0}, Case{10.0, 20.0}}) {
    FrictionalColumnProblem p = silo(0.0, 0);
    p.column.cells = {1, 1, 4};
    p.material = ColumnMaterial::drucker_prager;
    p.strength = {30.0, m.psi_deg, m.cohesion, ConeMatching::outer};
    p.newton.tolerance = 1e-12;
    const ColumnProblem& c = p.column;
    const double ka = rankine_active(30.0 * degree), k0 = analytic_k0(c.poisson_ratio);
    const double deepest = c.density * c.gravity * c.height;
    const double strain = (k0 - ka) * deepest * (1.0 - c.poisson_ratio) / c.youngs_modulus;
    for (const double share : {0.25, 2.0}) {
      p.loading.wall_displacement = {share * strain * c.length_x, share * strain * c.length_y};
      p.loading.relaxation_steps = 5;
      const FrictionalColumnSolution s = solve_frictional_column(p, MPI_COMM_WORLD, "");
      SCOPED_TRACE(::testing::Message() << "psi " << m.psi_deg << " c " << m.cohesion << " share " << share);
      double deviation = 0.0;  // largest |sigma_h - Rankine| / |sigma_zz| over the levels
      for (unsigned k = 0; k < c.cells[2]; ++k) {
        const auto& sigma = s.cell_average_stress[k];
        const double rankine = ka * sigma[8] + 2.0 * m.cohesion * std::sqrt(ka);
        const double scale = std::abs(sigma[8]);
        deviation =
            std::max({deviation, std::abs(sigma[0] - rankine) / scale, std::abs(sigma[4] - rankine) / scale});
        if (share > 1.0) {
          EXPECT_NEAR(sigma[0], rankine, 1e-9 * scale) << "level " << k;
          EXPECT_NEAR(sigma[4], rankine, 1e-9 * scale) << "level " << k;
        } else {
          // A quarter of the relaxation: the deep levels are still elastic, between K0 and
          // Rankine (compression negative: K0 sigma_zz <= sigma_xx <= Rankine); none is past
          // Rankine.
          EXPECT_LE(sigma[0], rankine + 1e-9 * scale) << "level " << k;
          EXPECT_GE(sigma[0], k0 * sigma[8] - 1e-9 * scale) << "level " << k;
          if (k == 0) {
            EXPECT_LT(sigma[0], rankine - 1e-3 * scale) << "the deepest level must still be elastic";
          }
        }
      }
      if (world_rank() == 0)
        std::printf(
            "  psi %.0f, c %.0f Pa, walls moved %.2f x the elastic relaxation: plastic share %.4f, largest "
            "|sigma_h - Rankine| / |sigma_zz| %.2e (K_a %.6f)\n",
            m.psi_deg, m.cohesion, share, s.plastic_volume_share, deviation, ka);
      if (share > 1.0) {
        EXPECT_NEAR(s.plastic_volume_share, 1.0, 1e-12);
      }
    }
  }
}

// With no cohesion, rigid walls and gravity as the only load, the problem is homogeneous of
// degree one in g: if (u, sigma) is the answer for g, (a u, a sigma) is the answer for a g.
// The loading path is then radial and the answer does not depend on the load steps
// (Drucker–Prager, walls slipping and sticking alike).
TEST(FrictionalColumn, CohesionlessAnswerDoesNotDependOnTheLoadSteps) {
  FrictionalColumnProblem p = silo(0.5, 0);
  p.column.cells = {2, 2, 3};
  p.walls.floor = 0.5;
  p.material = ColumnMaterial::drucker_prager;
  p.newton.tolerance = 1e-12;
  const FrictionalColumnSolution one = solve_frictional_column(p, MPI_COMM_WORLD, "");
  p.loading.load_steps = 3;
  const FrictionalColumnSolution three = solve_frictional_column(p, MPI_COMM_WORLD, "");
  EXPECT_GT(one.plastic_volume_share, 0.0);
  EXPECT_LT(largest_difference(p, one, three, "1 load step vs 3"), 1e-9);
}

// Newton's method with the consistent tangent converges quadratically near the solution:
// r_{k+1} = C r_k^2, so the order log(r_{k+1}/r_k) / log(r_k/r_{k-1}) tends to 2. Measured on
// the last three residuals above round-off (|r|/|f| > 1e-13; the floor is ~1e-15 here), for
// friction on an elastic column and on a non-associated Drucker–Prager one (both tangents
// unsymmetric). The cases are ones whose Newton sequence has three iterates in the
// asymptotic range: a stiff wall friction with nu = 0.4 (elastic), and a column with
// nu = 0.2 whose at-rest state lies outside the cone, so that 97 % of it yields. The
// residuals are printed per iteration (NewtonControl::log).
TEST(FrictionalColumn, NewtonConvergesQuadratically) {
  struct Case {
    ColumnMaterial material;
    double poisson_ratio, friction;
  };
  for (const Case& c :
       {Case{ColumnMaterial::elastic, 0.4, 0.8}, Case{ColumnMaterial::drucker_prager, 0.2, 0.3}}) {
    FrictionalColumnProblem p = silo(c.friction, 0);
    p.column.cells = {2, 2, 3};
    p.column.poisson_ratio = c.poisson_ratio;
    p.walls.floor = c.friction;
    p.material = c.material;
    p.newton.tolerance = 1e-14;
    p.newton.log = true;
    const FrictionalColumnSolution s = solve_frictional_column(p, MPI_COMM_WORLD, "");
    ASSERT_EQ(s.load_steps.size(), 1u);
    std::vector<double> r = s.load_steps[0].residuals;
    while (!r.empty() && r.back() < 1e-13) r.pop_back();
    ASSERT_GE(r.size(), 3u);
    const std::size_t k = r.size() - 2;
    const double order = std::log(r[k + 1] / r[k]) / std::log(r[k] / r[k - 1]);
    if (world_rank() == 0)
      std::printf("  Newton order %.3f from |r|/|f| = %.3e, %.3e, %.3e\n", order, r[k - 1], r[k], r[k + 1]);
    EXPECT_GT(order, 1.8) << "material " << static_cast<int>(c.material);
  }
}

// Partitioning must not change the answer beyond the solver tolerance: the 2-rank solve
// (MPI_COMM_WORLD under mpiexec -n 2) against a 1-rank solve on each rank (MPI_COMM_SELF).
// Drucker–Prager with wall and floor friction on an uneven mesh, in two load steps.
TEST(FrictionalColumn, OneAndTwoRanksAgree) {
  FrictionalColumnProblem p = silo(0.4, 0);
  p.column.cells = {2, 3, 5};
  p.column.length_x = 0.015;
  p.walls.side = {0.4, 0.3, 0.5, 0.4};
  p.walls.floor = 0.5;
  p.material = ColumnMaterial::drucker_prager;
  p.strength.dilatancy_angle_deg = 10.0;
  p.loading.load_steps = 2;
  p.newton.tolerance = 1e-12;
  const FrictionalColumnSolution parallel = solve_frictional_column(p, MPI_COMM_WORLD, "");
  const FrictionalColumnSolution serial = solve_frictional_column(p, MPI_COMM_SELF, "");
  EXPECT_EQ(parallel.n_dofs, serial.n_dofs);
  EXPECT_LT(largest_difference(p, parallel, serial, "communicator of all ranks vs one rank"), 1e-9);
  EXPECT_NEAR(parallel.side_wall_vertical_force, serial.side_wall_vertical_force, 1e-9 * serial.weight);
  EXPECT_NEAR(parallel.plastic_volume_share, serial.plastic_volume_share, 1e-12);
  if (world_rank() == 0)
    std::printf("  2 ranks vs 1: plastic share %.4f, wall share %.5f vs %.5f\n",
                parallel.plastic_volume_share, parallel.side_wall_vertical_force / parallel.weight,
                serial.side_wall_vertical_force / serial.weight);
}

// Newton's method that cannot converge (one iteration allowed where friction needs more)
// is bisected down to 1/16 of the step and then reported as NewtonFailure on every rank,
// naming the load step; no rank is left waiting.
TEST(FrictionalColumn, NewtonFailureIsReportedOnEveryRank) {
  FrictionalColumnProblem p = silo(0.5, 0);
  p.column.cells = {1, 1, 2};
  p.newton.tolerance = 1e-12;
  p.newton.max_iterations = 1;
  try {
    (void)solve_frictional_column(p, MPI_COMM_WORLD, "");
    ADD_FAILURE() << "no NewtonFailure";
  } catch (const NewtonFailure& e) {
    EXPECT_NE(std::string(e.what()).find("load step 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("4 bisections"), std::string::npos) << e.what();
  }
}

TEST(FrictionalColumn, BadInputNamesTheParameter) {
  const auto expect_refused = [](const FrictionalColumnProblem& p, const std::string& name) {
    try {
      (void)solve_frictional_column(p, MPI_COMM_WORLD, "");
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  FrictionalColumnProblem good = silo(0.3, 0);
  good.material = ColumnMaterial::drucker_prager;
  FrictionalColumnProblem p = good;
  p.column.poisson_ratio = 0.5;
  expect_refused(p, "poisson_ratio");
  for (const double phi : {0.0, 90.0, std::nan("")}) {
    p = good;
    p.strength.friction_angle_deg = phi;
    expect_refused(p, "strength.friction_angle_deg");
  }
  p = good;
  p.strength.dilatancy_angle_deg = 35.0;  // above phi = 30
  expect_refused(p, "strength.dilatancy_angle_deg");
  p = good;
  p.strength.cohesion = -1.0;
  expect_refused(p, "strength.cohesion");
  p = good;
  p.walls.side[2] = -0.1;
  expect_refused(p, "walls.side[2]");
  p = good;
  p.walls.floor = INFINITY;
  expect_refused(p, "walls.floor");
  p = good;
  p.walls.penalty_factor = 0.0;
  expect_refused(p, "walls.penalty_factor");
  p = good;
  p.loading.load_steps = 0;
  expect_refused(p, "loading.load_steps");
  p = good;
  p.loading.wall_displacement = {1e-6, 0.0};
  expect_refused(p, "loading.relaxation_steps");
  p = good;
  p.loading.wall_displacement = {0.0, -1e-6};
  expect_refused(p, "loading.wall_displacement[1]");
  p = good;
  p.newton.tolerance = 0.0;
  expect_refused(p, "newton.tolerance");
}

}  // namespace
}  // namespace upgrain::fem
