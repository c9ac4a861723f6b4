#include "dem/io/grid_stress_output.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/io/grid_xdmf.h"
#include "dem/io/hdf5_util.h"
#include "dem/stress/asymmetry.h"

namespace upgrain::dem::io {

namespace {

constexpr const char* kSignConvention =
    "sigma_ij = (1/V) sum f_i l_j: first index the force, second the branch (t_i = sigma_ij n_j); "
    "compression negative; Pa";
constexpr const char* kVolume = "V = grid cell volume; grains belong to the cell of their centroid";

}  // namespace

RegularGrid stress_grid(const GridStressOptions& options, const ParticleStore& p, const BoxContainer& box) {
  RegularGrid g;
  for (int d = 0; d < 3; ++d) g.n[d] = options.cells[d];
  if (options.fixed_box) {
    g.lo = options.lo;
    g.hi = options.hi;
    return g;
  }
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  g.lo = Vec3::Zero();
  g.hi = Vec3(box.lx, box.ly, top > 0.0 ? top : box.height);
  // The unconstrained collapse spreads past the footprint once the side walls are gone:
  // the grid then spans the grains' horizontal extent as well.
  if (box.opens_side_walls())
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int d = 0; d < 2; ++d) {
        g.lo[d] = std::min(g.lo[d], p.x[i][d] - p.radius[i]);
        g.hi[d] = std::max(g.hi[d], p.x[i][d] + p.radius[i]);
      }
  return g;
}

std::string field_name(StressFormula f) {
  std::string s(name_of(f));
  for (char& c : s)
    if (c == ' ') c = '_';
  return s;
}

void write_grid_stress(const std::filesystem::path& path, const RegularGrid& grid, const GridStress& stress,
                       const std::vector<StressFormula>& formulas, double time, long step) {
  using namespace hdf5;
  const auto cells = static_cast<hsize_t>(grid.num_cells());
  AtomicFile target(path);
  {
    Handle file(hdf5::create_file(target.temporary_path()), H5Fclose,
                "create " + target.temporary_path().string());
    write_attribute(file, "time", time);
    write_attribute(file, "step", static_cast<double>(step));
    write_attribute(file, "sign_convention", kSignConvention);
    write_attribute(file, "volume", kVolume);
    {
      Handle g(create_group(file, "grid"), H5Gclose, "create group grid");
      write_dataset(g, "lo", grid.lo.data(), 3, 1);
      write_dataset(g, "hi", grid.hi.data(), 3, 1);
      write_dataset(g, "n", grid.n, 3, 1);
      write_attribute(g, "cell_volume", stress.cell_volume);
    }
    {
      Handle g(create_group(file, "cells"), H5Gclose, "create group cells");
      const struct {
        const char* name;
        const std::vector<long>* data;
      } counts[] = {{"particles", &stress.particles},
                    {"internal_contacts", &stress.internal_contacts},
                    {"external_contacts", &stress.external_contacts},
                    {"wall_contacts", &stress.wall_contacts}};
      for (const auto& c : counts) write_dataset(g, c.name, c.data->data(), cells, 1);
      write_dataset(g, "solid_fraction", stress.solid_fraction.data(), cells, 1);
    }
    Handle sg(create_group(file, "stress"), H5Gclose, "create group stress");
    for (StressFormula f : formulas) {
      Handle g(create_group(sg, field_name(f)), H5Gclose, "create group " + field_name(f));
      std::vector<double> tensor(9 * cells), rai(cells), szz(cells);
      for (hsize_t c = 0; c < cells; ++c) {
        const Mat3& s = stress[f][c];
        for (int e = 0; e < 9; ++e) tensor[9 * c + e] = s(e / 3, e % 3);
        rai[c] = relative_asymmetry_index(s);
        szz[c] = s(2, 2);
      }
      write_dataset(g, "tensor", tensor.data(), cells, 9);
      write_dataset(g, "rai", rai.data(), cells, 1);
      write_dataset(g, "sigma_zz", szz.data(), cells, 1);
    }
    hdf5::flush(file, target.final_path().string());
  }
  target.commit();
}

GridStressRecorder::GridStressRecorder(std::filesystem::path folder, std::vector<StressFormula> formulas)
    : folder_(std::move(folder)),
      formulas_(std::move(formulas)),
      csv_(folder_ / "grid_stress.csv",
           std::string("# Upgrain grid stress. ") + kSignConvention + ". " + kVolume +
               ". rai = relative asymmetry index (fraction, 2-norm).\n"
               "time,step,cell,i,j,k,x,y,z,formula,s_xx,s_xy,s_xz,s_yx,s_yy,s_yz,s_zx,s_zy,s_zz,rai,"
               "particles,internal_contacts,external_contacts,wall_contacts,solid_fraction\n") {
  create_folder(folder_ / "grid_stress");
}

void GridStressRecorder::resume(const std::vector<GridStressEntry>& entries, long csv_rows) {
  entries_ = entries;
  csv_.resume(csv_rows);
  flush();
}

void GridStressRecorder::record(const RegularGrid& grid, const GridStress& stress, double time, long step) {
  char name[64];
  std::snprintf(name, sizeof name, "grid_stress_%09ld.h5", step);
  const std::string rel = (std::filesystem::path("grid_stress") / name).string();
  write_grid_stress(folder_ / rel, grid, stress, formulas_, time, step);
  entries_.push_back({rel, time, step, grid});
  std::string rows;
  for (int c = 0; c < grid.num_cells(); ++c) {
    const int i = c % grid.n[0], j = (c / grid.n[0]) % grid.n[1], k = c / (grid.n[0] * grid.n[1]);
    const Vec3 x = grid.cell_centre(c);
    for (StressFormula f : formulas_) {
      const Mat3& s = stress[f][c];
      char line[768];
      std::snprintf(
          line, sizeof line,
          "%.9g,%ld,%d,%d,%d,%d,%.17g,%.17g,%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%."
          "17g,%.17g,%ld,%ld,%ld,%ld,%.17g\n",
          time, step, c, i, j, k, x.x(), x.y(), x.z(), field_name(f).c_str(), s(0, 0), s(0, 1), s(0, 2),
          s(1, 0), s(1, 1), s(1, 2), s(2, 0), s(2, 1), s(2, 2), relative_asymmetry_index(s),
          stress.particles[c], stress.internal_contacts[c], stress.external_contacts[c],
          stress.wall_contacts[c], stress.solid_fraction[c]);
      rows += line;
    }
  }
  csv_.append(rows);
  flush();
}

void GridStressRecorder::flush() const {
  std::vector<GridXdmfStep> steps;
  for (const GridStressEntry& e : entries_) {
    GridXdmfStep step{e.file, e.time, e.step, e.grid, {}};
    step.attributes.push_back({"particles", "Scalar", "/cells/particles", 1, "Int", 8});
    step.attributes.push_back({"solid_fraction", "Scalar", "/cells/solid_fraction"});
    for (StressFormula f : formulas_) {
      const std::string n = field_name(f);
      step.attributes.push_back({n, "Tensor", "/stress/" + n + "/tensor", 9});
      step.attributes.push_back({n + "_sigma_zz", "Scalar", "/stress/" + n + "/sigma_zz"});
      step.attributes.push_back({n + "_rai", "Scalar", "/stress/" + n + "/rai"});
    }
    steps.push_back(std::move(step));
  }
  write_grid_xdmf(folder_ / "grid_stress.xdmf", "grid_stress", steps);
}

}  // namespace upgrain::dem::io
