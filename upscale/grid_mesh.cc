// Grid fields on a deal.II mesh (docs/upscale.md). The one translation unit of the upscale
// module that includes deal.II. Steps, in the order of upscale_to_mesh():
//   make_mesh()        one coarse cell per grid cell, refined globally;
//   attach_cell_data() each active cell takes the value of the grid cell holding its centre;
//   read_back()        the cell-data vectors read again through each grid cell's coarse cell;
//   project()          L2 projection onto continuous Q1 (M u = b), with integrals and means;
//   write_output()     VTU pieces and a PVTU record, renamed into place when all are complete.
#include "upscale/grid_mesh.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <system_error>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/files/output_journal.h"
#include "dem/files/undated_vtk.h"

namespace upgrain::upscale {

namespace {

using namespace dealii;
namespace fs = std::filesystem;

// CG stops when ||b - M u|| <= kRelativeTolerance ||b||.
constexpr double kRelativeTolerance = 1e-12;

// Throws the same upgrain::Error on every rank when any rank failed: the message of the
// lowest failing rank. Collective.
void check_all(MPI_Comm comm, bool ok, const std::string& message) {
  const int rank = Utilities::MPI::this_mpi_process(comm);
  const int size = Utilities::MPI::n_mpi_processes(comm);
  int first_failed = ok ? size : rank;
  MPI_Allreduce(MPI_IN_PLACE, &first_failed, 1, MPI_INT, MPI_MIN, comm);
  if (first_failed == size) return;
  std::string text = rank == first_failed ? message : std::string();
  unsigned long length = text.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG, first_failed, comm);
  text.resize(length);
  MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, first_failed, comm);
  throw Error(rank == first_failed ? text : text + " (on rank " + std::to_string(first_failed) + ")");
}

// Runs `step` on this rank, then check_all(): a failure on one rank throws on every rank
// instead of leaving the others waiting in a collective call.
template <class Step>
void on_every_rank(MPI_Comm comm, Step&& step) {
  bool ok = true;
  std::string message;
  try {
    step();
  } catch (const std::exception& e) {
    ok = false;
    message = e.what();
  }
  check_all(comm, ok, message);
}

// deal.II accepts these characters in data names (DataOut asserts it in Debug only).
bool valid_name(const std::string& s) {
  return !s.empty() &&
         s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_<>()") ==
             std::string::npos;
}

void validate(const GridFields& f, const std::string& basename) {
  for (int d = 0; d < 3; ++d) {
    if (f.n[d] < 1)
      throw Error("upscale: the grid has " + std::to_string(f.n[d]) + " cells along axis " + "xyz"[d]);
    if (!(f.hi[d] > f.lo[d])) throw Error(std::string("upscale: the grid box is empty along ") + "xyz"[d]);
  }
  if (f.names.size() != f.values.size())
    throw Error("upscale: " + std::to_string(f.names.size()) + " field names for " +
                std::to_string(f.values.size()) + " fields");
  std::set<std::string> taken{"subdomain"};
  for (std::size_t k = 0; k < f.names.size(); ++k) {
    const std::string& name = f.names[k];
    if (!valid_name(name))
      throw Error("upscale: field name '" + name + "' must be letters, digits and _ only (VTU data names)");
    if (f.values[k].size() != static_cast<std::size_t>(f.num_cells()))
      throw Error("upscale: field " + name + " has " + std::to_string(f.values[k].size()) +
                  " values, the grid has " + std::to_string(f.num_cells()) + " cells");
    if (!taken.insert(name).second || !taken.insert(name + "_q1").second)
      throw Error("upscale: field name " + name + " clashes with another field or its _q1 projection");
  }
  if (basename.empty() || basename.find('/') != std::string::npos)
    throw Error("upscale: output basename '" + basename + "' must be a plain file name");
}

class GridToMesh {
 public:
  GridToMesh(const GridFields& fields, MPI_Comm comm) : f_(fields), comm_(comm), tria_(comm) {}

  UpscaleResult run(const fs::path& folder, const std::string& basename, const UpscaleOptions& options) {
    make_mesh(options.refinements);
    attach_cell_data();
    read_back();
    if (options.project_q1) project();
    write_output(folder, basename);
    return std::move(result_);
  }

 private:
  [[nodiscard]] std::size_t num_fields() const { return f_.names.size(); }

  // The grid cell holding `x`, (k ny + j) nx + i. Called with cell centres only, which lie
  // half a mesh cell away from any grid face, so the rounding of the division never decides.
  [[nodiscard]] int grid_cell_of(const Point<3>& x) const {
    int c[3];
    for (int d = 0; d < 3; ++d) {
      const double s = (x[d] - f_.lo[d]) / (f_.hi[d] - f_.lo[d]) * f_.n[d];
      c[d] = std::clamp(static_cast<int>(std::floor(s)), 0, f_.n[d] - 1);
    }
    return (c[2] * f_.n[1] + c[1]) * f_.n[0] + c[0];
  }

  void make_mesh(unsigned refinements) {
    GridGenerator::subdivided_hyper_rectangle(
        tria_,
        {static_cast<unsigned>(f_.n[0]), static_cast<unsigned>(f_.n[1]), static_cast<unsigned>(f_.n[2])},
        Point<3>(f_.lo[0], f_.lo[1], f_.lo[2]), Point<3>(f_.hi[0], f_.hi[1], f_.hi[2]));
    tria_.refine_global(refinements);
    dof_handler_.reinit(tria_);
    dof_handler_.distribute_dofs(fe_);
  }

  // Cellwise-constant data: one value per active cell (the vectors are indexed by
  // active_cell_index over the local part of the mesh, as DataOut wants them); only locally
  // owned cells are filled.
  void attach_cell_data() {
    grid_cell_.assign(tria_.n_active_cells(), -1);
    for (const auto& cell : tria_.active_cell_iterators())
      if (cell->is_locally_owned()) grid_cell_[cell->active_cell_index()] = grid_cell_of(cell->center());
    cell_data_.assign(num_fields(), Vector<double>(tria_.n_active_cells()));
    for (std::size_t k = 0; k < num_fields(); ++k)
      for (std::size_t a = 0; a < grid_cell_.size(); ++a)
        if (grid_cell_[a] >= 0) cell_data_[k][a] = f_.values[k][grid_cell_[a]];
  }

  // Independent of attach_cell_data's lookup from fine-cell centres: each owned cell's
  // coarse ancestor (which is exactly one grid cell) names the grid cell, and the value is
  // read from the cell-data vector. Min and max over all the mesh cells of a grid cell, on
  // all ranks, must agree; the value is then exact.
  void read_back() {
    const std::size_t cells = f_.num_cells();
    std::vector<double> lo(num_fields() * cells, std::numeric_limits<double>::infinity());
    std::vector<double> hi(num_fields() * cells, -std::numeric_limits<double>::infinity());
    for (const auto& cell : tria_.active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      Triangulation<3>::cell_iterator coarse = cell;
      while (coarse->level() > 0) coarse = coarse->parent();
      const std::size_t g = grid_cell_of(coarse->center());
      for (std::size_t k = 0; k < num_fields(); ++k) {
        const double v = cell_data_[k][cell->active_cell_index()];
        lo[k * cells + g] = std::min(lo[k * cells + g], v);
        hi[k * cells + g] = std::max(hi[k * cells + g], v);
      }
    }
    MPI_Allreduce(MPI_IN_PLACE, lo.data(), static_cast<int>(lo.size()), MPI_DOUBLE, MPI_MIN, comm_);
    MPI_Allreduce(MPI_IN_PLACE, hi.data(), static_cast<int>(hi.size()), MPI_DOUBLE, MPI_MAX, comm_);
    result_.cell_values_read_back.assign(num_fields(), std::vector<double>(cells));
    for (std::size_t k = 0; k < num_fields(); ++k)
      for (std::size_t g = 0; g < cells; ++g) {
        const double a = lo[k * cells + g], b = hi[k * cells + g];
        // std::min/max drop NaN inputs in one order and keep them in the other; a NaN field
        // value reads back as NaN either way.
        result_.cell_values_read_back[k][g] = a == b ? a : std::numeric_limits<double>::quiet_NaN();
      }
  }

  // L2 projection of each cellwise-constant field f_h onto continuous Q1: find u_h with
  // (u_h, phi_i) = (f_h, phi_i) for every shape function, i.e. M u = b with
  // M_ij = int phi_i phi_j, b_i = int phi_i f_h. Two-point Gauss quadrature integrates both
  // exactly on these affine hexahedra. M is shared by all fields. A field with a
  // non-finite value is not projected (its results are NaN).
  void project() {
    const IndexSet owned = dof_handler_.locally_owned_dofs();
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler_, relevant);
    AffineConstraints<double> constraints(relevant);  // hanging nodes: none after global refinement
    DoFTools::make_hanging_node_constraints(dof_handler_, constraints);
    constraints.close();

    DynamicSparsityPattern dsp(relevant);
    DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp, owned, comm_, relevant);
    TrilinosWrappers::SparseMatrix mass;
    mass.reinit(owned, owned, dsp, comm_);
    std::vector<TrilinosWrappers::MPI::Vector> rhs(num_fields(), TrilinosWrappers::MPI::Vector(owned, comm_));
    TrilinosWrappers::MPI::Vector lumped(owned, comm_);  // M 1 = int phi_i

    projected_.assign(num_fields(), false);
    for (std::size_t k = 0; k < num_fields(); ++k)
      projected_[k] =
          std::all_of(f_.values[k].begin(), f_.values[k].end(), [](double x) { return std::isfinite(x); });

    const QGauss<3> quadrature(2);
    FEValues<3> fe_values(fe_, quadrature, update_values | update_JxW_values);
    const unsigned dofs = fe_.n_dofs_per_cell();
    FullMatrix<double> cell_mass(dofs, dofs);
    Vector<double> phi_integral(dofs), cell_rhs(dofs);
    std::vector<types::global_dof_index> indices(dofs);
    for (const auto& cell : dof_handler_.active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      fe_values.reinit(cell);
      cell_mass = 0;
      phi_integral = 0;
      for (unsigned q = 0; q < quadrature.size(); ++q)
        for (unsigned i = 0; i < dofs; ++i) {
          const double phi_i = fe_values.shape_value(i, q) * fe_values.JxW(q);
          phi_integral(i) += phi_i;
          for (unsigned j = 0; j < dofs; ++j) cell_mass(i, j) += phi_i * fe_values.shape_value(j, q);
        }
      cell->get_dof_indices(indices);
      constraints.distribute_local_to_global(cell_mass, indices, mass);
      constraints.distribute_local_to_global(phi_integral, indices, lumped);
      for (std::size_t k = 0; k < num_fields(); ++k) {
        if (!projected_[k]) continue;
        cell_rhs = phi_integral;
        cell_rhs *= cell_data_[k][cell->active_cell_index()];
        constraints.distribute_local_to_global(cell_rhs, indices, rhs[k]);
      }
    }
    mass.compress(VectorOperation::add);
    lumped.compress(VectorOperation::add);
    for (auto& b : rhs) b.compress(VectorOperation::add);

    TrilinosWrappers::PreconditionJacobi jacobi;
    jacobi.initialize(mass);
    q1_.assign(num_fields(), TrilinosWrappers::MPI::Vector(owned, relevant, comm_));
    for (std::size_t k = 0; k < num_fields(); ++k) {
      if (!projected_[k]) continue;
      TrilinosWrappers::MPI::Vector u(owned, comm_);
      // Start from the lumped-mass solution b_i / int phi_i: exact for a constant field.
      for (const auto i : owned) u[i] = rhs[k][i] / lumped[i];
      u.compress(VectorOperation::insert);
      const double norm_b = rhs[k].l2_norm();
      if (norm_b > 0.0) {
        SolverControl control(1000, kRelativeTolerance * norm_b);
        SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
        cg.solve(mass, u, rhs[k], jacobi);
        result_.max_cg_iterations = std::max(result_.max_cg_iterations, control.last_step());
      }
      constraints.distribute(u);
      q1_[k] = u;
    }
    integrate();
  }

  // Integrals over the box and means over each grid cell of u_h, and the integral of f_h.
  void integrate() {
    const std::size_t cells = f_.num_cells();
    const QGauss<3> quadrature(2);  // exact for trilinear u_h on affine cells
    FEValues<3> fe_values(fe_, quadrature, update_values | update_JxW_values);
    std::vector<double> values(quadrature.size());
    // [field][grid cell] integral of u_h, then one row with the grid cells' volumes.
    std::vector<double> sums((num_fields() + 1) * cells, 0.0), cellwise(num_fields(), 0.0);
    for (const auto& cell : dof_handler_.active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      fe_values.reinit(cell);
      const std::size_t g = grid_cell_[cell->active_cell_index()];
      double volume = 0.0;
      for (unsigned q = 0; q < quadrature.size(); ++q) volume += fe_values.JxW(q);
      sums[num_fields() * cells + g] += volume;
      for (std::size_t k = 0; k < num_fields(); ++k) {
        cellwise[k] += cell_data_[k][cell->active_cell_index()] * volume;
        if (!projected_[k]) continue;
        fe_values.get_function_values(q1_[k], values);
        double integral = 0.0;
        for (unsigned q = 0; q < quadrature.size(); ++q) integral += values[q] * fe_values.JxW(q);
        sums[k * cells + g] += integral;
      }
    }
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM, comm_);
    MPI_Allreduce(MPI_IN_PLACE, cellwise.data(), static_cast<int>(cellwise.size()), MPI_DOUBLE, MPI_SUM,
                  comm_);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    result_.q1_cell_means.assign(num_fields(), std::vector<double>(cells, nan));
    result_.q1_integral.assign(num_fields(), nan);
    result_.cellwise_integral = cellwise;
    for (std::size_t k = 0; k < num_fields(); ++k) {
      if (!projected_[k]) continue;
      double total = 0.0;
      for (std::size_t g = 0; g < cells; ++g) {
        total += sums[k * cells + g];
        result_.q1_cell_means[k][g] = sums[k * cells + g] / sums[num_fields() * cells + g];
      }
      result_.q1_integral[k] = total;
    }
  }

  // Pieces <basename>.<rank>.vtu and the record <basename>.pvtu are written into a fresh
  // hidden folder next to the output, then renamed into it, pieces first: the record that
  // ParaView opens appears last and only when everything it names is complete. On an error
  // the hidden folder is removed and nothing appears.
  void write_output(const fs::path& folder, const std::string& basename) {
    const unsigned rank = Utilities::MPI::this_mpi_process(comm_);
    const unsigned ranks = Utilities::MPI::n_mpi_processes(comm_);
    const unsigned digits = Utilities::needed_digits(ranks - 1);
    auto piece = [&](unsigned r) { return basename + "." + Utilities::int_to_string(r, digits) + ".vtu"; };
    const std::string record = basename + ".pvtu";

    int pid = static_cast<int>(::getpid());
    MPI_Bcast(&pid, 1, MPI_INT, 0, comm_);
    const fs::path staging = folder / ("." + basename + ".tmp." + std::to_string(pid));
    struct RemoveStaging {
      fs::path path;
      bool active;
      ~RemoveStaging() {
        std::error_code ec;
        if (!active) return;
        fs::remove_all(path, ec);
        try {
          if (!ec) dem::io::note_removed(path);
        } catch (const std::exception&) {
          // The manifest then still lists the folder as being written: a leftover of the run.
        }
      }
    } cleanup{staging, rank == 0};

    on_every_rank(comm_, [&] {
      if (rank != 0) return;
      std::error_code ec;
      dem::io::create_folder(folder);
      // The staging folder first, then the names it will give (docs/output.md, "Manifest").
      dem::io::note_writing(staging);
      for (unsigned r = 0; r < ranks; ++r) dem::io::note_writing(folder / piece(r));
      dem::io::note_writing(folder / record);
      fs::remove_all(staging, ec);  // left by a crashed run with the same process id
      if (!fs::create_directory(staging, ec) || ec)
        throw Error("upscale: cannot create " + staging.string() + ": " + ec.message());
    });

    DataOut<3> data_out;
    data_out.attach_dof_handler(dof_handler_);
    for (std::size_t k = 0; k < num_fields(); ++k)
      data_out.add_data_vector(cell_data_[k], f_.names[k], DataOut<3>::type_cell_data);
    for (std::size_t k = 0; k < q1_.size(); ++k)
      if (projected_[k]) data_out.add_data_vector(q1_[k], f_.names[k] + "_q1", DataOut<3>::type_dof_data);
    Vector<float> subdomain(tria_.n_active_cells());
    subdomain = static_cast<float>(tria_.locally_owned_subdomain());
    data_out.add_data_vector(subdomain, "subdomain", DataOut<3>::type_cell_data);
    data_out.build_patches();
    DataOutBase::VtkFlags flags(f_.time, static_cast<unsigned>(std::max(0L, f_.step)), false,
                                DataOutBase::VtkFlags::best_speed);
    data_out.set_flags(flags);

    auto write = [&](const std::string& name, auto&& body) {
      const fs::path path = staging / name;
      std::ofstream out(path, std::ios::binary);
      if (!out) throw Error("upscale: cannot open " + path.string());
      body(out);
      out.close();
      if (!out) throw Error("upscale: error while writing " + path.string());
    };
    on_every_rank(comm_, [&] { write(piece(rank), [&](std::ostream& out) { data_out.write_vtu(out); }); });
    std::vector<std::string> pieces;
    for (unsigned r = 0; r < ranks; ++r) pieces.push_back(piece(r));
    on_every_rank(comm_, [&] {
      if (rank != 0) return;
      write(record, [&](std::ostream& out) {
        std::ostringstream text;
        data_out.write_pvtu_record(text, pieces);
        out << dem::io::undated_vtk(text.str());
      });
      for (const std::string& name : pieces) fs::rename(staging / name, folder / name);
      fs::rename(staging / record, folder / record);
      for (const std::string& name : pieces) dem::io::note_written(folder / name);
      dem::io::note_written(folder / record);
    });

    result_.written_files.push_back((folder / record).string());
    for (const std::string& name : pieces) result_.written_files.push_back((folder / name).string());
  }

  const GridFields& f_;
  MPI_Comm comm_;
  parallel::distributed::Triangulation<3> tria_;
  FE_Q<3> fe_{1};
  DoFHandler<3> dof_handler_;
  std::vector<int> grid_cell_;  // [active cell index] grid cell of a locally owned cell, else -1
  std::vector<Vector<double>> cell_data_;
  std::vector<TrilinosWrappers::MPI::Vector> q1_;  // ghosted, for DataOut and integration
  std::vector<bool> projected_;
  UpscaleResult result_;
};

}  // namespace

UpscaleResult upscale_to_mesh(const GridFields& fields, MPI_Comm comm, const fs::path& folder,
                              const std::string& basename, const UpscaleOptions& options) {
  validate(fields, basename);
  GridToMesh mapping(fields, comm);
  return mapping.run(folder, basename, options);
}

}  // namespace upgrain::upscale
