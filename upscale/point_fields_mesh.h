#pragma once
// Fields given at points (the coarse-grained fields, docs/coarse-graining.md) on the
// continuum's deal.II mesh, beside its stress: evaluated at the mesh's support points (a
// continuous Q_k field) or at its quadrature points (cell means), compared with the
// continuum's stress in the L2 norm over the mesh, and written as VTU pieces with a PVTU
// record. deal.II is confined to point_fields_mesh.cc: this header needs only MPI.
#include <mpi.h>

#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace upgrain::upscale {

// The study's mesh: a box split into cells (one per stress-grid cell), refined globally,
// with the continuum's polynomial degree (the same mesh as fem::solve_column's).
struct MeshBox {
  std::array<double, 3> lo{}, hi{};
  std::array<unsigned, 3> cells{1, 1, 1};
  unsigned refinements = 0;
  unsigned degree = 1;
};

enum class MeshPoints { support, quadrature };

// The continuum's stress at the Gauss points (degree + 1 per direction) of this rank's cells
// (fem::QuadratureStress): position, weight JxW, sigma row-major.
struct StressAtPoints {
  std::vector<std::array<double, 3>> x;
  std::vector<double> weight;
  std::vector<std::array<double, 9>> sigma;
};

// Scalar fields at points, [field][point]. The nine "s_xx", "s_xy", ..., "s_zz" (row-major
// sigma_ij) are compared with the continuum's stress.
struct PointValues {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
};
// Collective: every rank calls it once with its own points.
using PointEvaluation = std::function<PointValues(const std::vector<std::array<double, 3>>& points)>;

struct MeshFieldComparison {
  // ||s_ij - sigma_h,ij||_L2 over the mesh (Gauss quadrature of the continuum), and
  // ||sigma_h,zz||_L2.
  std::array<double, 9> l2_difference{};
  double l2_continuum_zz = 0.0;
  // int (s_xx + s_yy) / 2 over int s_zz, over the mesh.
  double lateral_ratio = 0.0;
  // Per horizontal level of quadrature points, bottom to top: z, mean s_zz, and the spread
  // (max - min) / |mean| of s_zz across the level.
  std::vector<double> level_z, level_mean_szz, level_spread;
  std::vector<std::string> written_files;  // the .pvtu, then the pieces
  unsigned long points = 0;                // evaluation points over all ranks
};

// Collective. Writes <folder>/<basename>.pvtu and its pieces: each field "cg_<name>" (point
// data at support points, cell means at quadrature points), the continuum's "fem_s_<ij>" and
// "diff_s_<ij>" (cell means of the field less the continuum, six components) and
// "subdomain". The mesh must be partitioned as the continuum's (the same box, cells,
// refinements and communicator): upgrain::Error on every rank otherwise.
MeshFieldComparison write_point_fields_on_mesh(const MeshBox& mesh, MeshPoints where,
                                               const StressAtPoints& continuum,
                                               const PointEvaluation& evaluate, MPI_Comm comm,
                                               const std::filesystem::path& folder,
                                               const std::string& basename, double time, long step);

}  // namespace upgrain::upscale
