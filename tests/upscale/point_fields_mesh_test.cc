// Fields at points on the continuum's mesh (docs/coarse-graining.md, "On the mesh"), against
// the continuum itself: the confined column's stress is linear in z, which Q2 reproduces, so a
// field that returns the exact stress differs from the continuum's by the solver's tolerance
// only, one offset by a constant c differs by |c| sqrt(V) in the L2 norm, the lateral ratio is
// K0 and every level is uniform; at support and at quadrature points, on 1 and 2 ranks (the
// mpiexec registration); a mesh split otherwise is refused.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <filesystem>

#include "dem/core/error.h"
#include "fem/elastic_column.h"
#include "upscale/point_fields_mesh.h"

using namespace upgrain;
namespace fs = std::filesystem;

namespace {

fem::ColumnProblem column() {
  fem::ColumnProblem p;
  p.length_x = 0.02;
  p.length_y = 0.02;
  p.height = 0.03;
  p.density = 1600;
  p.youngs_modulus = 1e8;
  p.poisson_ratio = 0.3;
  p.cells = {2, 2, 3};
  p.refinements = 1;
  p.degree = 2;
  p.keep_quadrature_stress = true;
  return p;
}

upscale::MeshBox mesh_of(const fem::ColumnProblem& p) {
  upscale::MeshBox m;
  m.hi = {p.length_x, p.length_y, p.height};
  m.cells = p.cells;
  m.refinements = p.refinements;
  m.degree = p.degree;
  return m;
}

// The exact stress of the column, plus `offset` on sigma_zz, as the nine fields s_ij.
upscale::PointEvaluation exact_stress(const fem::ConfinedColumn& exact, double offset) {
  return [exact, offset](const std::vector<std::array<double, 3>>& x) {
    upscale::PointValues v;
    const char* comp[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
    for (int e = 0; e < 9; ++e) {
      v.names.push_back(std::string("s_") + comp[e]);
      std::vector<double> c(x.size(), 0.0);
      for (std::size_t q = 0; q < x.size(); ++q) {
        const double szz = exact.vertical_stress(x[q][2]);
        if (e == 8) c[q] = szz + offset;
        if (e == 0 || e == 4) c[q] = exact.k0() * szz;
      }
      v.values.push_back(std::move(c));
    }
    return v;
  };
}

fs::path scratch(const std::string& name) {
  int pid = static_cast<int>(::getpid());
  MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return fs::temp_directory_path() / ("upgrain_point_fields_" + name + "_" + std::to_string(pid));
}

TEST(PointFieldsOnMesh, ExactStressAgreesWithTheContinuumAtSupportAndQuadraturePoints) {
  const fem::ColumnProblem p = column();
  const fem::ColumnSolution sol = fem::solve_column(p, MPI_COMM_WORLD, "");
  const fem::ConfinedColumn exact = fem::analytic_solution(p);
  const upscale::StressAtPoints continuum{sol.quadrature_stress.x, sol.quadrature_stress.weight,
                                          sol.quadrature_stress.sigma};
  const double volume = p.length_x * p.length_y * p.height, c = 123.0;
  for (auto where : {upscale::MeshPoints::support, upscale::MeshPoints::quadrature}) {
    const fs::path dir = scratch(where == upscale::MeshPoints::support ? "support" : "quadrature");
    const upscale::MeshFieldComparison same = upscale::write_point_fields_on_mesh(
        mesh_of(p), where, continuum, exact_stress(exact, 0.0), MPI_COMM_WORLD, dir, "f", 0.0, 0);
    // The continuum equals the exact column to its solver's tolerance (1e-12 relative).
    for (int e = 0; e < 9; ++e) EXPECT_LE(same.l2_difference[e], 1e-9 * same.l2_continuum_zz) << e;
    EXPECT_NEAR(same.lateral_ratio, exact.k0(), 1e-9);
    ASSERT_EQ(same.level_z.size(), 6u * 3u);  // 6 layers of cells, 3 Gauss points each
    for (double spread : same.level_spread) EXPECT_LE(spread, 1e-9);
    EXPECT_EQ(same.points, where == upscale::MeshPoints::support ? 9u * 9u * 13u : 96u * 27u);
    const upscale::MeshFieldComparison shifted = upscale::write_point_fields_on_mesh(
        mesh_of(p), where, continuum, exact_stress(exact, c), MPI_COMM_WORLD, dir, "f", 0.0, 0);
    EXPECT_NEAR(shifted.l2_difference[8], c * std::sqrt(volume), 1e-9 * c * std::sqrt(volume));
    EXPECT_LE(shifted.l2_difference[0], 1e-9 * shifted.l2_continuum_zz);
    EXPECT_TRUE(fs::exists(dir / "f.pvtu"));
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    EXPECT_EQ(shifted.written_files.size(), static_cast<std::size_t>(size) + 1);
    MPI_Barrier(MPI_COMM_WORLD);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) fs::remove_all(dir);
  }
}

TEST(PointFieldsOnMesh, AMeshSplitOtherwiseIsRefused) {
  const fem::ColumnProblem p = column();
  const fem::ColumnSolution sol = fem::solve_column(p, MPI_COMM_WORLD, "");
  const upscale::StressAtPoints continuum{sol.quadrature_stress.x, sol.quadrature_stress.weight,
                                          sol.quadrature_stress.sigma};
  upscale::MeshBox other = mesh_of(p);
  other.cells = {3, 2, 3};
  EXPECT_THROW((void)upscale::write_point_fields_on_mesh(other, upscale::MeshPoints::quadrature, continuum,
                                                         exact_stress(fem::analytic_solution(p), 0.0),
                                                         MPI_COMM_WORLD, scratch("refused"), "f", 0.0, 0),
               Error);
}

}  // namespace
