// The deal.II column solver against the exact solution of the laterally confined column
// (fem/analytic/confined_column.h, docs/fem.md). Every test runs on all ranks of
// MPI_COMM_WORLD: CTest runs this binary plain and under `mpiexec -n 2`.
//
// Assertions use EXPECT_* only around collective calls: an ASSERT failing on one rank
// would return early and leave the other rank waiting in the next collective.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "../common/world.h"
#include "fem/elastic_column.h"

namespace upgrain::fem {
namespace {

using test::world_rank;
using test::world_size;

// The default DEM scene's box (4.5 cm square) filled 6 cm high with a bed of bulk density
// 1600 kg/m^3, as a continuum with E = 50 MPa, nu = 0.3; the DEM stress grid is 3x3x4.
ColumnProblem bed(unsigned degree, unsigned refinements) {
  ColumnProblem p;
  p.length_x = 0.045;
  p.length_y = 0.045;
  p.height = 0.06;
  p.density = 1600.0;
  p.youngs_modulus = 5.0e7;
  p.poisson_ratio = 0.3;
  p.cells = {3, 3, 4};
  p.degree = degree;
  p.refinements = refinements;
  return p;
}

struct RelativeErrors {
  double displacement, stress;
};
RelativeErrors relative_errors(const ColumnProblem& p, const ColumnSolution& s) {
  const ConfinedColumn exact = analytic_solution(p);
  const double area = p.length_x * p.length_y;
  return {s.l2_error_displacement / exact.displacement_l2_norm(area),
          s.l2_error_stress / exact.stress_l2_norm(area)};
}

// Coarse-cell averages against the exact ones: sigma_zz = mean over the cell's slab,
// sigma_xx = sigma_yy = K0 sigma_zz, no shear. Tolerances relative to the cell's sigma_zz;
// the measured deviations are below 2e-13 for every case in this file.
void expect_exact_coarse_averages(const ColumnProblem& p, const ColumnSolution& s, double tolerance) {
  const ConfinedColumn exact = analytic_solution(p);
  const unsigned nx = p.cells[0], ny = p.cells[1], nz = p.cells[2];
  ASSERT_EQ(s.cell_average_stress.size(), std::size_t{nx} * ny * nz);
  const double dz = p.height / nz;
  for (unsigned iz = 0; iz < nz; ++iz)
    for (unsigned iy = 0; iy < ny; ++iy)
      for (unsigned ix = 0; ix < nx; ++ix) {
        const auto& sigma = s.cell_average_stress[coarse_cell_index(p, ix, iy, iz)];
        const double szz = exact.mean_vertical_stress(iz * dz, (iz + 1) * dz);
        const double scale = std::abs(szz);
        SCOPED_TRACE("coarse cell (" + std::to_string(ix) + "," + std::to_string(iy) + "," +
                     std::to_string(iz) + ")");
        EXPECT_NEAR(sigma[8], szz, tolerance * scale);
        EXPECT_NEAR(sigma[0] / sigma[8], exact.k0(), tolerance);
        EXPECT_NEAR(sigma[4] / sigma[8], exact.k0(), tolerance);
        for (int k : {1, 2, 3, 5, 6, 7}) EXPECT_NEAR(sigma[k], 0.0, tolerance * scale) << "component " << k;
      }
}

// One row of the verification table in docs/fem.md, printed by rank 0.
void print_table_header() {
  if (world_rank() == 0)
    std::printf(
        "| degree | refinements | cells | dofs | CG its | rel. L2 error u | rate | rel. L2 error sigma | "
        "rate | "
        "solve (s) | total (s) |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
}
void print_table_row(const ColumnProblem& p, const ColumnSolution& s, const RelativeErrors& e,
                     const RelativeErrors* previous) {
  if (world_rank() != 0) return;
  char rate_u[16] = "", rate_sigma[16] = "";
  if (previous) {
    std::snprintf(rate_u, sizeof rate_u, "%.6f", std::log2(previous->displacement / e.displacement));
    std::snprintf(rate_sigma, sizeof rate_sigma, "%.6f", std::log2(previous->stress / e.stress));
  }
  std::printf("| Q%u | %u | %lu | %lu | %u | %.6e | %s | %.6e | %s | %.3f | %.3f |\n", p.degree,
              p.refinements, static_cast<unsigned long>(s.n_active_cells),
              static_cast<unsigned long>(s.n_dofs), s.cg_iterations, e.displacement, rate_u, e.stress,
              rate_sigma, s.solve_seconds, s.total_seconds);
}

// The exact displacement is quadratic in z, so Q2 contains it: the discrete solution is
// the exact one up to the CG tolerance (relative residual 1e-12).
void check_quadratic_elements(unsigned max_refinements) {
  for (unsigned refinements = 0; refinements <= max_refinements; ++refinements) {
    const ColumnProblem p = bed(2, refinements);
    const ColumnSolution s = solve_column(p, MPI_COMM_WORLD, "");
    const RelativeErrors e = relative_errors(p, s);
    print_table_row(p, s, e, nullptr);
    // Measured: below 1e-13 on 1 and 2 ranks.
    EXPECT_LT(e.displacement, 1e-10);
    EXPECT_LT(e.stress, 1e-10);
    expect_exact_coarse_averages(p, s, 1e-10);
  }
}

// Q1 cannot represent the quadratic u_z: the L2 error of u falls as h^2 and that of sigma
// as h. Here more holds. The discrete solution is the 1D one (u_x = u_y = 0 exactly,
// docs/fem.md) and 1D linear elements are exact at the nodes of this problem, so the
// errors are exactly the interpolation errors, with h the vertical cell size:
//   ||u_h - u|| / ||u|| = (h/H)^2 / 4,   ||sigma_h - sigma|| / ||sigma|| = (h/H) / 2,
// the rates are 2 and 1 up to round-off, and the coarse averages of sigma are exact even
// for Q1 (each cell's constant sigma_h is the exact mean over the cell).
void check_linear_elements(unsigned max_refinements) {
  RelativeErrors previous{};
  for (unsigned refinements = 0; refinements <= max_refinements; ++refinements) {
    const ColumnProblem p = bed(1, refinements);
    const ColumnSolution s = solve_column(p, MPI_COMM_WORLD, "");
    const RelativeErrors e = relative_errors(p, s);
    print_table_row(p, s, e, refinements > 0 ? &previous : nullptr);
    const double h_over_H = 1.0 / (p.cells[2] << refinements);
    // Measured deviation from the closed forms: <= 2e-11 relative (round-off relative to
    // an error that shrinks with h).
    EXPECT_NEAR(e.displacement / (0.25 * h_over_H * h_over_H), 1.0, 1e-9);
    EXPECT_NEAR(e.stress / (0.5 * h_over_H), 1.0, 1e-9);
    if (refinements > 0) {
      EXPECT_NEAR(std::log2(previous.displacement / e.displacement), 2.0, 0.01);
      EXPECT_NEAR(std::log2(previous.stress / e.stress), 1.0, 0.01);
    }
    expect_exact_coarse_averages(p, s, 1e-10);
    previous = e;
  }
}

TEST(ElasticColumn, QuadraticElementsReproduceTheExactSolution) {
  print_table_header();
  check_quadratic_elements(1);
}

TEST(ElasticColumn, LinearElementsConvergeAtTheExpectedRates) {
  print_table_header();
  check_linear_elements(2);
}

// The table of docs/fem.md, one refinement further than the tests above (~10 s on one
// core). Run it with
//   fem_tests --gtest_also_run_disabled_tests --gtest_filter='*VerificationTable*'
TEST(ElasticColumn, DISABLED_VerificationTable) {
  print_table_header();
  check_linear_elements(3);
  check_quadratic_elements(2);
}

// Partitioning must not change the answer beyond the solver tolerance. Under mpiexec -n 2
// this compares the 2-rank solve (MPI_COMM_WORLD) with a 1-rank solve on each rank
// (MPI_COMM_SELF); run plain, both are 1-rank solves. Q1 on an uneven coarse mesh, so the
// solution carries a discretisation error that depends on the mesh, not only on the exact
// solution; nu = 0.2 and a different box exercise other numbers than the tests above.
TEST(ElasticColumn, OneAndTwoRanksAgree) {
  ColumnProblem p = bed(1, 1);
  p.cells = {2, 3, 5};
  p.length_x = 0.03;
  p.poisson_ratio = 0.2;
  const ColumnSolution parallel = solve_column(p, MPI_COMM_WORLD, "");
  const ColumnSolution serial = solve_column(p, MPI_COMM_SELF, "");
  EXPECT_EQ(parallel.n_dofs, serial.n_dofs);
  EXPECT_NEAR(parallel.l2_error_displacement / serial.l2_error_displacement, 1.0, 1e-9);
  EXPECT_NEAR(parallel.l2_error_stress / serial.l2_error_stress, 1.0, 1e-9);
  ASSERT_EQ(parallel.cell_average_stress.size(), serial.cell_average_stress.size());
  const double scale = p.density * p.gravity * p.height;
  for (std::size_t c = 0; c < serial.cell_average_stress.size(); ++c)
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(parallel.cell_average_stress[c][k], serial.cell_average_stress[c][k], 1e-10 * scale);
  expect_exact_coarse_averages(p, parallel, 1e-10);
}

TEST(ElasticColumn, WritesPvtuAndPiecesAtomically) {
  const std::filesystem::path folder =
      std::filesystem::current_path() / ("fem_output_np" + std::to_string(world_size()));
  if (world_rank() == 0) std::filesystem::remove_all(folder);
  MPI_Barrier(MPI_COMM_WORLD);
  const ColumnSolution s = solve_column(bed(2, 0), MPI_COMM_WORLD, folder.string());
  EXPECT_TRUE(std::filesystem::is_regular_file(folder / "column.pvtu"));
  int n_files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    ++n_files;
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
  EXPECT_EQ(n_files, world_size() + 1);
  for (int r = 0; r < world_size(); ++r) {
    char name[32];
    std::snprintf(name, sizeof name, "column.proc%04d.vtu", r);
    EXPECT_GT(std::filesystem::file_size(folder / name), 0u) << name;
  }
  EXPECT_GT(s.total_seconds, 0.0);
}

TEST(ElasticColumn, OutputToAnUnwritablePlaceThrowsOnEveryRank) {
  // A regular file where the folder should be: creating the folder fails on every rank.
  const std::filesystem::path blocker =
      std::filesystem::current_path() / ("fem_blocker_np" + std::to_string(world_size()));
  if (world_rank() == 0) {
    std::filesystem::remove_all(blocker);
    std::FILE* f = std::fopen(blocker.c_str(), "w");
    if (f) std::fclose(f);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_THROW(solve_column(bed(1, 0), MPI_COMM_WORLD, (blocker / "out").string()), std::runtime_error);
}

// Each bad parameter is refused with its name in the message, before any communication.
TEST(ElasticColumn, BadInputNamesTheParameter) {
  const auto expect_refused = [](const ColumnProblem& p, const std::string& name) {
    try {
      (void)solve_column(p, MPI_COMM_WORLD, "");
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  const ColumnProblem good = bed(1, 0);
  ColumnProblem p = good;
  p.length_x = 0.0;
  expect_refused(p, "length_x");
  p = good;
  p.length_y = -1.0;
  expect_refused(p, "length_y");
  p = good;
  p.height = std::nan("");
  expect_refused(p, "height");
  p = good;
  p.density = 0.0;
  expect_refused(p, "density");
  p = good;
  p.gravity = -9.81;
  expect_refused(p, "gravity");
  p = good;
  p.youngs_modulus = 0.0;
  expect_refused(p, "youngs_modulus");
  for (double nu : {0.5, -1.0, 0.7}) {
    p = good;
    p.poisson_ratio = nu;
    expect_refused(p, "poisson_ratio");
  }
  p = good;
  p.cells = {3, 0, 4};
  expect_refused(p, "cells[1]");
  p = good;
  p.degree = 0;
  expect_refused(p, "degree");
  p = good;
  p.refinements = 11;
  expect_refused(p, "refinements");
  ColumnProblem unset;  // sizes default to zero: they must be given
  expect_refused(unset, "length_x");
}

}  // namespace
}  // namespace upgrain::fem
