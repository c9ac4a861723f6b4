#pragma once
// What the deal.II column solvers share (elastic_column.cc, frictional_column.cc): the box
// mesh whose coarse cells are the DEM stress grid's cells, the map from a fine cell to its
// coarse cell, the coarse-cell averages, and the atomic .vtu/.pvtu output. Private to
// upgrain::fem: it includes deal.II, so only those two translation units include it.
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <p4est_base.h>
#include <sc.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dem/files/atomic_file.h"
#include "dem/files/output_journal.h"
#include "dem/files/undated_vtk.h"
#include "fem/elastic_column.h"
#include "fem/pvtu_pieces.h"

namespace upgrain::fem::column_mesh {

constexpr int dim = 3;

// Boundary ids set by GridGenerator::subdivided_hyper_rectangle(..., colorize = true):
// 2d is the face x_d = min, 2d+1 the face x_d = max.
constexpr dealii::types::boundary_id wall_x0 = 0, wall_x1 = 1, wall_y0 = 2, wall_y1 = 3, floor_z0 = 4;

// deal.II's MPI_InitFinalize registers p4est with the log threshold SC_LP_SILENT. A caller
// that uses plain MPI_Init (the upgrain driver, fem_tests) does not, and p4est then logs
// every mesh operation to stdout. Do the same, once, unless someone already has.
inline void silence_p4est() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (p4est_package_id < 0) p4est_init(nullptr, SC_LP_SILENT);
  });
}

// The box [0,Lx]x[0,Ly]x[0,H] with (nx, ny, nz) coarse cells, colorized, refined globally.
inline void make_grid(dealii::parallel::distributed::Triangulation<dim>& triangulation,
                      const ColumnProblem& p) {
  const std::vector<unsigned int> repetitions(p.cells.begin(), p.cells.end());
  dealii::GridGenerator::subdivided_hyper_rectangle(triangulation, repetitions,
                                                    dealii::Point<dim>(0.0, 0.0, 0.0),
                                                    dealii::Point<dim>(p.length_x, p.length_y, p.height),
                                                    /*colorize=*/true);
  triangulation.refine_global(p.refinements);
}

// The coarse cell that contains a fine cell's centre.
inline unsigned int coarse_cell_of(const ColumnProblem& p, const dealii::Point<dim>& centre) {
  std::array<unsigned int, dim> index;
  const double size[dim] = {p.length_x, p.length_y, p.height};
  for (unsigned int d = 0; d < dim; ++d) {
    // The centre of a fine cell lies strictly inside its coarse cell, so the floor is
    // unambiguous; the clamp only guards against round-off at the far wall.
    const double i = std::floor(centre[d] / size[d] * p.cells[d]);
    index[d] = static_cast<unsigned int>(std::clamp(i, 0.0, p.cells[d] - 1.0));
  }
  return coarse_cell_index(p, index[0], index[1], index[2]);
}

// Per coarse cell, the 9 components of int sigma dx summed over this rank's fine cells.
class CoarseStressIntegrals {
 public:
  explicit CoarseStressIntegrals(const ColumnProblem& p) : problem_(p), sums_(9 * n_coarse_cells(p), 0.0) {}
  // Adds a fine cell's integral of sigma (any type with [i][j]).
  template <class Tensor>
  void add(const dealii::Point<dim>& fine_cell_centre, const Tensor& integral) {
    double* sum = &sums_[9 * coarse_cell_of(problem_, fine_cell_centre)];
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j) sum[dim * i + j] += integral[i][j];
  }
  // Sums over the ranks and divides by the coarse-cell volume: the same on every rank.
  [[nodiscard]] std::vector<std::array<double, 9>> averages(MPI_Comm comm) const {
    std::vector<double> global(sums_.size());
    dealii::Utilities::MPI::sum(sums_, comm, global);
    const ColumnProblem& p = problem_;
    const double volume = p.length_x / p.cells[0] * p.length_y / p.cells[1] * p.height / p.cells[2];
    std::vector<std::array<double, 9>> out(n_coarse_cells(p));
    for (std::size_t c = 0; c < out.size(); ++c)
      for (unsigned int k = 0; k < 9; ++k) out[c][k] = global[9 * c + k] / volume;
    return out;
  }

 private:
  ColumnProblem problem_;
  std::vector<double> sums_;
};

// The six independent stress components, in the order the solvers store their cell
// averages for output.
inline const std::array<std::pair<unsigned int, unsigned int>, 6> stress_components = {
    {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
inline const std::array<const char*, 6> stress_names = {"sigma_xx", "sigma_yy", "sigma_zz",
                                                        "sigma_xy", "sigma_xz", "sigma_yz"};

// What both solvers write: the displacement, the cell averages of sigma, any further cell
// fields, and the subdomain, through write_pieces_and_record. Each cell is subdivided
// degree times so that Q2 displacements are drawn as such.
template <class DisplacementVector>
void write_column(const dealii::DoFHandler<dim>& dof_handler, const DisplacementVector& displacement,
                  const std::array<dealii::Vector<double>, 6>& cell_stress,
                  const std::vector<std::pair<std::string, const dealii::Vector<double>*>>& cell_fields,
                  const std::string& folder, MPI_Comm comm) {
  using dealii::DataOut;
  DataOut<dim> data_out;
  data_out.attach_dof_handler(dof_handler);
  const std::vector<std::string> names(dim, "displacement");
  const std::vector<dealii::DataComponentInterpretation::DataComponentInterpretation> interpretation(
      dim, dealii::DataComponentInterpretation::component_is_part_of_vector);
  data_out.add_data_vector(displacement, names, DataOut<dim>::type_dof_data, interpretation);
  for (unsigned int k = 0; k < 6; ++k)
    data_out.add_data_vector(cell_stress[k], stress_names[k], DataOut<dim>::type_cell_data);
  for (const auto& [name, field] : cell_fields)
    data_out.add_data_vector(*field, name, DataOut<dim>::type_cell_data);
  const auto& triangulation = dof_handler.get_triangulation();
  dealii::Vector<float> subdomain(triangulation.n_active_cells());
  for (auto& s : subdomain) s = static_cast<float>(triangulation.locally_owned_subdomain());
  data_out.add_data_vector(subdomain, "subdomain");
  data_out.build_patches(dof_handler.get_fe().degree);
  write_pieces_and_record(data_out, folder, "column", comm);
}

}  // namespace upgrain::fem::column_mesh
