// Fields at points on the continuum's mesh (docs/coarse-graining.md, "On the mesh"). The one
// translation unit of it that includes deal.II. Steps, in write_point_fields_on_mesh():
//   make_mesh()          the continuum's mesh (same box, cells, refinements, partition);
//   place_continuum()    each of the continuum's quadrature points into this rank's cell;
//   evaluate()           the fields at support points (nodal Q_k) or quadrature points;
//   compare()            L2 differences, lateral ratio, level spreads, cell means;
//   write_output()       VTU pieces and a PVTU record, the record last.
#include "upscale/point_fields_mesh.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/files/output_journal.h"
#include "dem/files/undated_vtk.h"
#include "dem/parallel/exchange.h"

namespace upgrain::upscale {

namespace {

using namespace dealii;
namespace fs = std::filesystem;
using DistributedVector = LinearAlgebra::distributed::Vector<double>;

constexpr const char* kComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
constexpr int kSymmetric[6] = {0, 4, 8, 1, 2, 5};

class PointFieldsOnMesh {
 public:
  PointFieldsOnMesh(const MeshBox& box, MPI_Comm comm)
      : box_(box), comm_(comm), tria_(comm), fe_(box.degree), quadrature_(box.degree + 1) {}

  MeshFieldComparison run(MeshPoints where, const StressAtPoints& continuum, const PointEvaluation& evaluate,
                          const fs::path& folder, const std::string& basename, double time, long step) {
    make_mesh();
    place_continuum(continuum);
    evaluate_fields(where, continuum, evaluate);
    compare(continuum);
    write_output(folder, basename, time, step);
    return std::move(result_);
  }

 private:
  void make_mesh() {
    GridGenerator::subdivided_hyper_rectangle(tria_, {box_.cells[0], box_.cells[1], box_.cells[2]},
                                              Point<3>(box_.lo[0], box_.lo[1], box_.lo[2]),
                                              Point<3>(box_.hi[0], box_.hi[1], box_.hi[2]));
    tria_.refine_global(box_.refinements);
    dofs_.reinit(tria_);
    dofs_.distribute_dofs(fe_);
    for (int d = 0; d < 3; ++d) fine_[d] = box_.cells[d] << box_.refinements;
  }

  // The finest-level cell (i + nx (j + ny k)) holding x.
  [[nodiscard]] long fine_cell_of(const std::array<double, 3>& x) const {
    long c[3];
    for (int d = 0; d < 3; ++d) {
      const double s = (x[d] - box_.lo[d]) / (box_.hi[d] - box_.lo[d]) * fine_[d];
      c[d] = std::clamp(static_cast<long>(std::floor(s)), 0L, static_cast<long>(fine_[d]) - 1);
    }
    return c[0] + static_cast<long>(fine_[0]) * (c[1] + static_cast<long>(fine_[1]) * c[2]);
  }

  // Each continuum quadrature point into this rank's cell: first_[cell] .. first_[cell] + nq
  // are its points, in the continuum's order (which is the order of FEValues' points).
  void place_continuum(const StressAtPoints& c) {
    const unsigned nq = quadrature_.size();
    std::map<long, unsigned> owned;  // fine cell -> active cell index (per cell, not per point)
    for (const auto& cell : tria_.active_cell_iterators())
      if (cell->is_locally_owned())
        owned[fine_cell_of({cell->center()[0], cell->center()[1], cell->center()[2]})] =
            cell->active_cell_index();
    first_.assign(tria_.n_active_cells(), -1);
    std::string error;
    if (c.x.size() != c.weight.size() || c.x.size() != c.sigma.size() || c.x.size() % nq != 0)
      error = "fields on the mesh: the continuum's quadrature points do not come " + std::to_string(nq) +
              " to a cell";
    for (std::size_t p = 0; error.empty() && p < c.x.size(); p += nq) {
      const auto it = owned.find(fine_cell_of(c.x[p]));
      if (it == owned.end()) {
        error =
            "fields on the mesh: the continuum's mesh is partitioned otherwise (a quadrature point lies in "
            "a cell this rank does not own)";
        break;
      }
      first_[it->second] = static_cast<long>(p);
    }
    if (error.empty() && c.x.size() / nq != owned.size())
      error = "fields on the mesh: the continuum has " + std::to_string(c.x.size() / nq) +
              " cells on this rank, the mesh " + std::to_string(owned.size());
    dem::throw_if_any(comm_, error);
  }

  void evaluate_fields(MeshPoints where, const StressAtPoints& c, const PointEvaluation& evaluate) {
    at_support_ = where == MeshPoints::support;
    if (!at_support_) {
      values_ = evaluate(c.x);
      result_.points = Utilities::MPI::sum(static_cast<unsigned long>(c.x.size()), comm_);
    } else {
      const IndexSet owned = dofs_.locally_owned_dofs();
      IndexSet relevant;
      DoFTools::extract_locally_relevant_dofs(dofs_, relevant);
      std::map<types::global_dof_index, Point<3>> support;
      DoFTools::map_dofs_to_support_points(MappingQ1<3>(), dofs_, support);
      std::vector<std::array<double, 3>> points;
      std::vector<types::global_dof_index> index;
      for (const auto& [i, x] : support)
        if (owned.is_element(i)) {
          points.push_back({x[0], x[1], x[2]});
          index.push_back(i);
        }
      values_ = evaluate(points);
      result_.points = Utilities::MPI::sum(static_cast<unsigned long>(points.size()), comm_);
      nodal_.assign(values_.names.size(), DistributedVector(owned, relevant, comm_));
      for (std::size_t f = 0; f < values_.names.size(); ++f) {
        for (std::size_t p = 0; p < index.size(); ++p) nodal_[f](index[p]) = values_.values[f][p];
        nodal_[f].update_ghost_values();
      }
    }
    for (int e = 0; e < 9; ++e) {
      const auto it =
          std::find(values_.names.begin(), values_.names.end(), std::string("s_") + kComponents[e]);
      if (it == values_.names.end())
        throw Error(std::string("fields on the mesh: no field s_") + kComponents[e]);
      stress_field_[e] = static_cast<int>(it - values_.names.begin());
    }
  }

  // The fields' values at the continuum's quadrature points of one cell (from the nodal
  // fields, or the points' own values).
  void values_at_quadrature(FEValues<3>& fe_values, long first, std::vector<std::vector<double>>& out) {
    const unsigned nq = quadrature_.size();
    out.resize(values_.names.size());
    for (std::size_t f = 0; f < values_.names.size(); ++f) {
      out[f].resize(nq);
      if (at_support_) {
        fe_values.get_function_values(nodal_[f], out[f]);
      } else {
        for (unsigned q = 0; q < nq; ++q) out[f][q] = values_.values[f][first + q];
      }
    }
  }

  void compare(const StressAtPoints& c) {
    FEValues<3> fe_values(fe_, quadrature_, update_values | update_quadrature_points | update_JxW_values);
    const unsigned nq = quadrature_.size();
    // Levels: the Gauss points' heights in each finest layer of cells.
    std::vector<double> level_z;
    const double h = (box_.hi[2] - box_.lo[2]) / fine_[2];
    for (unsigned k = 0; k < fine_[2]; ++k)
      for (unsigned q = 0; q < QGauss<1>(box_.degree + 1).size(); ++q)
        level_z.push_back(box_.lo[2] + (k + QGauss<1>(box_.degree + 1).point(q)[0]) * h);
    const std::size_t levels = level_z.size();
    std::vector<double> lo(levels, std::numeric_limits<double>::infinity()),
        hi(levels, -std::numeric_limits<double>::infinity()), sum(levels, 0.0), count(levels, 0.0);
    std::array<double, 9> diff2{};
    double fem_zz2 = 0.0, lateral = 0.0, vertical = 0.0;
    cell_mean_.assign(values_.names.size() + 12, Vector<double>(tria_.n_active_cells()));
    std::vector<std::vector<double>> at_q;
    std::string error;
    for (const auto& cell : dofs_.active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      fe_values.reinit(cell);
      const long first = first_[cell->active_cell_index()];
      values_at_quadrature(fe_values, first, at_q);
      double volume = 0.0;
      for (unsigned q = 0; q < nq; ++q) {
        const auto& x = c.x[first + q];
        const Point<3>& mine = fe_values.quadrature_point(q);
        if (std::abs(mine[0] - x[0]) + std::abs(mine[1] - x[1]) + std::abs(mine[2] - x[2]) >
            1e-9 * (box_.hi[2] - box_.lo[2]))
          error = "fields on the mesh: the continuum's quadrature points are not this mesh's";
        const double w = c.weight[first + q];
        volume += w;
        const std::array<double, 9>& fem = c.sigma[first + q];
        for (int e = 0; e < 9; ++e) diff2[e] += w * std::pow(at_q[stress_field_[e]][q] - fem[e], 2);
        fem_zz2 += w * fem[8] * fem[8];
        const double szz = at_q[stress_field_[8]][q];
        lateral += w * 0.5 * (at_q[stress_field_[0]][q] + at_q[stress_field_[4]][q]);
        vertical += w * szz;
        const std::size_t level = static_cast<std::size_t>(
            std::lower_bound(level_z.begin(), level_z.end(), x[2] - 1e-9 * h) - level_z.begin());
        if (level < levels) {
          lo[level] = std::min(lo[level], szz);
          hi[level] = std::max(hi[level], szz);
          sum[level] += szz;
          count[level] += 1.0;
        }
        for (std::size_t f = 0; f < values_.names.size(); ++f)
          cell_mean_[f][cell->active_cell_index()] += w * at_q[f][q];
        for (int k = 0; k < 6; ++k) {
          const int e = kSymmetric[k];
          cell_mean_[values_.names.size() + k][cell->active_cell_index()] += w * fem[e];
          cell_mean_[values_.names.size() + 6 + k][cell->active_cell_index()] +=
              w * (at_q[stress_field_[e]][q] - fem[e]);
        }
      }
      for (auto& m : cell_mean_) m[cell->active_cell_index()] /= volume;
    }
    dem::throw_if_any(comm_, error);
    for (int e = 0; e < 9; ++e) result_.l2_difference[e] = std::sqrt(Utilities::MPI::sum(diff2[e], comm_));
    result_.l2_continuum_zz = std::sqrt(Utilities::MPI::sum(fem_zz2, comm_));
    const double v = Utilities::MPI::sum(vertical, comm_);
    result_.lateral_ratio = v != 0.0 ? Utilities::MPI::sum(lateral, comm_) / v : 0.0;
    Utilities::MPI::min(lo, comm_, lo);
    Utilities::MPI::max(hi, comm_, hi);
    Utilities::MPI::sum(sum, comm_, sum);
    Utilities::MPI::sum(count, comm_, count);
    for (std::size_t l = 0; l < levels; ++l) {
      if (count[l] == 0.0) continue;
      const double mean = sum[l] / count[l];
      result_.level_z.push_back(level_z[l]);
      result_.level_mean_szz.push_back(mean);
      result_.level_spread.push_back(mean != 0.0 ? (hi[l] - lo[l]) / std::abs(mean) : 0.0);
    }
  }

  void write_output(const fs::path& folder, const std::string& basename, double time, long step) {
    const unsigned rank = Utilities::MPI::this_mpi_process(comm_);
    const unsigned ranks = Utilities::MPI::n_mpi_processes(comm_);
    const unsigned digits = Utilities::needed_digits(ranks - 1);
    auto piece = [&](unsigned r) { return basename + "." + Utilities::int_to_string(r, digits) + ".vtu"; };
    DataOut<3> data_out;
    data_out.attach_dof_handler(dofs_);
    for (std::size_t f = 0; f < values_.names.size(); ++f) {
      if (at_support_)
        data_out.add_data_vector(nodal_[f], "cg_" + values_.names[f], DataOut<3>::type_dof_data);
      else
        data_out.add_data_vector(cell_mean_[f], "cg_" + values_.names[f], DataOut<3>::type_cell_data);
    }
    for (int k = 0; k < 6; ++k) {
      const std::string comp = kComponents[kSymmetric[k]];
      data_out.add_data_vector(cell_mean_[values_.names.size() + k], "fem_s_" + comp,
                               DataOut<3>::type_cell_data);
      data_out.add_data_vector(cell_mean_[values_.names.size() + 6 + k], "diff_s_" + comp,
                               DataOut<3>::type_cell_data);
    }
    Vector<float> subdomain(tria_.n_active_cells());
    subdomain = static_cast<float>(tria_.locally_owned_subdomain());
    data_out.add_data_vector(subdomain, "subdomain", DataOut<3>::type_cell_data);
    data_out.build_patches(at_support_ ? box_.degree : 1);
    data_out.set_flags(DataOutBase::VtkFlags(time, static_cast<unsigned>(std::max(0L, step)), false,
                                             DataOutBase::VtkFlags::best_speed));
    std::vector<fs::path> piece_paths;
    for (unsigned r = 0; r < ranks; ++r) piece_paths.push_back(folder / piece(r));
    dem::io::note_pieces_writing(comm_, folder, piece_paths);  // docs/output.md, "Manifest"
    std::string error;
    try {
      std::ostringstream vtu;
      data_out.write_vtu(vtu);
      dem::io::write_text_atomically(folder / piece(rank), vtu.str());
    } catch (const std::exception& e) {
      error = e.what();
    }
    dem::throw_if_any(comm_, error);
    std::vector<std::string> pieces;
    for (unsigned r = 0; r < ranks; ++r) pieces.push_back(piece(r));
    if (rank == 0) {
      try {
        std::ostringstream pvtu;
        data_out.write_pvtu_record(pvtu, pieces);
        dem::io::write_text_atomically(folder / (basename + ".pvtu"), dem::io::undated_vtk(pvtu.str()));
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    dem::throw_if_any(comm_, error);
    dem::io::note_pieces_written(comm_, piece_paths);
    result_.written_files.push_back((folder / (basename + ".pvtu")).string());
    for (const std::string& p : pieces) result_.written_files.push_back((folder / p).string());
  }

  MeshBox box_;
  MPI_Comm comm_;
  parallel::distributed::Triangulation<3> tria_;
  FE_Q<3> fe_;
  QGauss<3> quadrature_;
  DoFHandler<3> dofs_;
  unsigned fine_[3] = {1, 1, 1};
  std::vector<long> first_;  // [active cell] first continuum quadrature point, or -1
  bool at_support_ = true;
  PointValues values_;
  std::vector<DistributedVector> nodal_;
  std::array<int, 9> stress_field_{};
  std::vector<Vector<double>> cell_mean_;  // fields, then fem (6), then differences (6)
  MeshFieldComparison result_;
};

}  // namespace

MeshFieldComparison write_point_fields_on_mesh(const MeshBox& mesh, MeshPoints where,
                                               const StressAtPoints& continuum,
                                               const PointEvaluation& evaluate, MPI_Comm comm,
                                               const fs::path& folder, const std::string& basename,
                                               double time, long step) {
  PointFieldsOnMesh m(mesh, comm);
  return m.run(where, continuum, evaluate, folder, basename, time, step);
}

}  // namespace upgrain::upscale
