#pragma once
// Linear elasticity of a gravity-loaded, laterally confined column: the continuum
// counterpart of a DEM deposition bed (docs/fem.md). This header is deal.II-free on
// purpose: consumers link upgrain::fem and need neither deal.II's include paths nor its
// flags. deal.II lives only in elastic_column.cc.
#include <mpi.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fem/analytic/confined_column.h"

namespace upgrain::fem {

struct ColumnProblem {
  // Container footprint [0,Lx]x[0,Ly] and fill height H (m). Zero defaults are rejected by
  // validate(): a size must be given.
  double length_x = 0.0;
  double length_y = 0.0;
  double height = 0.0;
  double density = 0.0;         // bulk density of the bed (kg/m^3)
  double gravity = 9.81;        // magnitude, acting in -z (m/s^2)
  double youngs_modulus = 0.0;  // E of the equivalent continuum (Pa)
  double poisson_ratio = 0.3;   // nu in (-1, 0.5)
  // Coarse mesh subdivisions (nx, ny, nz): one coarse cell per cell of the DEM stress grid.
  std::array<unsigned, 3> cells = {3, 3, 4};
  unsigned refinements = 1;  // global refinements of the coarse mesh (each halves h)
  unsigned degree = 1;       // polynomial degree of the FE_Q displacement element, 1 to 4
  // The wall x = Lx removed: that face is traction free and the column bulges out through it
  // under its weight, in shear (docs/hard-cases.md, the near-incompressible continuum). The
  // exact solution and the errors against it are then not this problem's.
  bool open_side_x1 = false;
  // Keep sigma_h at the quadrature points of this rank's cells (ColumnSolution::
  // quadrature_stress), for comparisons with fields at points (docs/coarse-graining.md).
  bool keep_quadrature_stress = false;
};

// The continuum's stress at the Gauss points (degree + 1 per direction) of the locally owned
// cells, cell by cell in the mesh's order: position, weight (JxW) and sigma_h row-major.
struct QuadratureStress {
  std::vector<std::array<double, 3>> x;
  std::vector<double> weight;
  std::vector<std::array<double, 9>> sigma;
};

// Every field holds the same value on every rank (reduced over the communicator), except the
// timings, which are the calling rank's wall-clock times.
struct ColumnSolution {
  // Volume average of sigma over each COARSE cell, row-major 3x3 (xx, xy, xz, yx, ...),
  // compression negative; index coarse_cell_index(problem, ix, iy, iz) = ix + nx (iy + ny iz).
  std::vector<std::array<double, 9>> cell_average_stress;
  // ||u_h - u||_L2 (m^2.5) and ||sigma_h - sigma||_L2 (Frobenius norm of the 3x3 tensor,
  // Pa m^1.5) against ConfinedColumn; absolute, divide by ConfinedColumn::*_l2_norm for
  // relative errors.
  double l2_error_displacement = 0.0;
  double l2_error_stress = 0.0;
  std::uint64_t n_dofs = 0;
  std::uint64_t n_active_cells = 0;
  unsigned cg_iterations = 0;
  double setup_seconds = 0.0;     // mesh, dofs, constraints, sparsity
  double assemble_seconds = 0.0;  // matrix and right-hand side
  double solve_seconds = 0.0;     // AMG setup plus CG
  double total_seconds = 0.0;     // the whole solve_column call, output included
  // This rank's, when ColumnProblem::keep_quadrature_stress (not reduced over the ranks).
  QuadratureStress quadrature_stress;
};

// Throws std::invalid_argument naming the first bad parameter.
void validate(const ColumnProblem& problem);

// The exact solution for the problem's data.
ConfinedColumn analytic_solution(const ColumnProblem& problem);

[[nodiscard]] inline unsigned coarse_cell_index(const ColumnProblem& problem, unsigned ix, unsigned iy,
                                                unsigned iz) {
  return ix + problem.cells[0] * (iy + problem.cells[1] * iz);
}
[[nodiscard]] inline unsigned n_coarse_cells(const ColumnProblem& problem) {
  return problem.cells[0] * problem.cells[1] * problem.cells[2];
}

// Solves the problem on the ranks of `comm` (collective). If `vtu_folder` is not empty the
// folder is created if needed and column.pvtu plus one column.proc<rank>.vtu per rank are
// written atomically: the .pvtu record appears last, only once every piece is complete.
// Throws std::invalid_argument on bad input (on every rank, before any communication),
// std::runtime_error if output fails on any rank, and deal.II's SolverControl::NoConvergence
// if CG does not converge.
ColumnSolution solve_column(const ColumnProblem& problem, MPI_Comm comm, const std::string& vtu_folder);

}  // namespace upgrain::fem
