#include "upscale/strain/grid_strain_output.h"

#include <cstdint>
#include <cstdio>
#include <sstream>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/io/grid_stress_output.h"
#include "dem/io/grid_xdmf.h"
#include "dem/io/hdf5_util.h"

namespace upgrain::upscale {

namespace hdf5 = dem::io::hdf5;
using dem::io::AtomicFile;
using dem::io::create_folder;
using dem::io::GridXdmfStep;
using dem::io::write_grid_xdmf;
using dem::io::write_text_atomically;

namespace {

constexpr const char* kConvention =
    "F maps reference (t0) to current positions, L current positions to velocities; tensors row-major "
    "T_ij at 3 i + j; invalid cells are zero with a reason code (reason_names)";

using hdf5::write_tensors;

void write_scalars(hid_t g, const char* name, const std::vector<double>& s) {
  hdf5::write_dataset(g, name, s.data(), s.size(), 1);
}

void write_reasons(hid_t g, const std::string& prefix, const std::vector<StrainReason>& r) {
  std::vector<std::int32_t> valid(r.size()), code(r.size());
  for (std::size_t c = 0; c < r.size(); ++c) {
    code[c] = static_cast<std::int32_t>(r[c]);
    valid[c] = r[c] == StrainReason::valid ? 1 : 0;
  }
  hdf5::write_dataset(g, (prefix + "_valid").c_str(), valid.data(), r.size(), 1);
  hdf5::write_dataset(g, (prefix + "_reason").c_str(), code.data(), r.size(), 1);
}

// How sigma_dot was taken at an output that used n outputs (grid_stress_rates.h).
std::string difference_name(int outputs_used) {
  if (outputs_used >= 3) return "backward, 3 outputs, second order (docs/strain.md eq. (10), last output)";
  if (outputs_used == 2) return "backward, 2 outputs, first order";
  return "none (first output)";
}

std::vector<std::string> reason_names() {
  std::vector<std::string> names;
  for (int r = 0; r < kStrainReasonCount; ++r) names.emplace_back(name_of(static_cast<StrainReason>(r)));
  return names;
}

// The columns from F_reason to residual_rms of a CSV row (strain_csv_header()).
void cell_columns(std::ostringstream& row, const CellStrainFields& f, int c) {
  row << ',' << static_cast<int>(f.f_reason[c]);
  for (int e = 0; e < 9; ++e) row << ',' << f.deformation_gradient[c](e / 3, e % 3);
  row << ',' << f.jacobian[c] << ',' << f.log_jacobian[c] << ',' << f.equivalent_shear_strain[c] << ','
      << static_cast<int>(f.l_reason[c]);
  for (int e = 0; e < 9; ++e) row << ',' << f.velocity_gradient[c](e / 3, e % 3);
  row << ',' << f.equivalent_shear_rate[c] << ',' << static_cast<int>(f.increment_reason[c]) << ','
      << f.increment_log_jacobian[c] << ',' << f.increment_equivalent_shear_strain[c] << ','
      << f.residual_rms[c];
}

constexpr const char* kCellColumns =
    "particles,F_reason,F_xx,F_xy,F_xz,F_yx,F_yy,F_yz,F_zx,F_zy,F_zz,J,ln_J,equivalent_shear_strain,L_reason,"
    "L_xx,L_xy,L_xz,L_yx,L_yy,L_yz,L_zx,L_zy,L_zz,equivalent_shear_rate,increment_reason,"
    "increment_ln_J,increment_equivalent_shear_strain,residual_rms";

std::string reason_legend() {
  std::ostringstream s;
  s << kConvention << ". Reason codes:";
  for (int r = 0; r < kStrainReasonCount; ++r)
    s << ' ' << r << " = " << name_of(static_cast<StrainReason>(r));
  return s.str();
}

// The attributes every strain file shares.
void write_strain_attributes(hid_t file, const GridStrain& strain) {
  using namespace hdf5;
  write_attribute(file, "time", strain.time);
  write_attribute(file, "step", static_cast<double>(strain.step));
  write_attribute(file, "reference_time", strain.reference_time);
  write_attribute(file, "reference_step", static_cast<double>(strain.reference_step));
  write_attribute(file, "set", std::string(name_of(strain.set)));
  write_attribute(file, "untracked", static_cast<double>(strain.untracked));
  write_attribute(file, "convention", kConvention);
  write_attribute(file, "reason_names", reason_names());
}

// One group per definition computed, with its fields per cell (and the rates when given).
void write_definitions(hid_t file, const GridStrain& strain, const GridStressRates* rates) {
  using namespace hdf5;
  for (int d = 0; d < kStrainDefinitionCount; ++d) {
    if (!strain.computed[d]) continue;
    const CellStrainFields& f = strain.fields[d];
    const std::string name = field_name(static_cast<StrainDefinition>(d));
    Handle g(create_group(file, name), H5Gclose, "create group " + name);
    write_tensors(g, "F", f.deformation_gradient);
    write_tensors(g, "L", f.velocity_gradient);
    write_tensors(g, "F_increment", f.increment);
    write_tensors(g, "E", f.green_lagrange);
    write_tensors(g, "e", f.euler_almansi);
    write_tensors(g, "hencky", f.hencky);
    write_tensors(g, "R", f.rotation);
    write_tensors(g, "D", f.rate_of_deformation);
    write_tensors(g, "W", f.spin);
    write_scalars(g, "J", f.jacobian);
    write_scalars(g, "ln_J", f.log_jacobian);
    write_scalars(g, "equivalent_shear_strain", f.equivalent_shear_strain);
    write_scalars(g, "equivalent_shear_rate", f.equivalent_shear_rate);
    write_scalars(g, "increment_ln_J", f.increment_log_jacobian);
    write_scalars(g, "increment_equivalent_shear_strain", f.increment_equivalent_shear_strain);
    write_scalars(g, "residual_rms", f.residual_rms);
    write_reasons(g, "F", f.f_reason);
    write_reasons(g, "L", f.l_reason);
    write_reasons(g, "increment", f.increment_reason);
    if (rates && rates->computed[d]) {
      const CellStressRates& r = rates->fields[d];
      write_tensors(g, "stress_rate", r.stress_rate);
      write_tensors(g, "jaumann_rate", r.jaumann);
      write_tensors(g, "green_naghdi_rate", r.green_naghdi);
      write_tensors(g, "truesdell_rate", r.truesdell);
      write_tensors(g, "oldroyd_rate", r.oldroyd);
      write_reasons(g, "rate", r.reason);
      write_reasons(g, "green_naghdi", r.green_naghdi_reason);
    }
  }
}

}  // namespace

std::string field_name(StrainDefinition d) {
  std::string s(name_of(d));
  for (char& c : s)
    if (c == ' ') c = '_';
  return s;
}

void write_grid_strain(const std::filesystem::path& path, const GridStrain& strain,
                       const GridStressRates* rates) {
  using namespace hdf5;
  const RegularGrid& grid = strain.grid;
  const auto cells = static_cast<hsize_t>(grid.num_cells());
  AtomicFile target(path);
  {
    Handle file(hdf5::create_file(target.temporary_path()), H5Fclose,
                "create " + target.temporary_path().string());
    write_strain_attributes(file, strain);
    {
      Handle g(create_group(file, "grid"), H5Gclose, "create group grid");
      write_dataset(g, "lo", grid.lo.data(), 3, 1);
      write_dataset(g, "hi", grid.hi.data(), 3, 1);
      write_dataset(g, "n", grid.n, 3, 1);
    }
    {
      Handle g(create_group(file, "cells"), H5Gclose, "create group cells");
      write_dataset(g, "particles", strain.particles.data(), cells, 1);
    }
    write_definitions(file, strain, rates);
    if (rates) {
      Handle g(create_group(file, "rates"), H5Gclose, "create group rates");
      write_attribute(g, "formula", dem::io::field_name(rates->formula));
      write_attribute(g, "outputs_used", static_cast<double>(rates->outputs_used));
      write_attribute(g, "order", static_cast<double>(rates->order()));
      write_attribute(g, "difference", difference_name(rates->outputs_used));
      write_tensors(g, "stress", rates->stress);
    }
    hdf5::flush(file, target.final_path().string());
  }
  target.commit();
}

namespace {
std::string strain_csv_header() {
  std::ostringstream csv;
  csv << "# Upgrain grid strain. " << reason_legend() << ".\ntime,step,reference_time,set,cell,i,j,k,x,y,z,"
      << "definition," << kCellColumns << ",rate_reason,green_naghdi_reason";
  for (const char* rate : {"jaumann", "green_naghdi", "truesdell", "oldroyd"})
    for (const char* comp : {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"})
      csv << ',' << rate << '_' << comp;
  csv << '\n';
  return csv.str();
}
}  // namespace

GridStrainRecorder::GridStrainRecorder(std::filesystem::path folder)
    : folder_(std::move(folder)), csv_(folder_ / "grid_strain.csv", strain_csv_header()) {
  create_folder(folder_ / "grid_strain");
}

void GridStrainRecorder::record(const GridStrain& strain, const GridStressRates* rates) {
  char name[64];
  std::snprintf(name, sizeof name, "grid_strain_%09ld.h5", strain.step);
  const std::string rel = (std::filesystem::path("grid_strain") / name).string();
  write_grid_strain(folder_ / rel, strain, rates);
  entries_.push_back({rel, strain.time, strain.step, strain.grid, strain.computed, rates != nullptr});
  const RegularGrid& grid = strain.grid;
  std::string rows;
  for (int c = 0; c < grid.num_cells(); ++c) {
    const int i = c % grid.n[0], j = (c / grid.n[0]) % grid.n[1], k = c / (grid.n[0] * grid.n[1]);
    const Vec3 x = grid.cell_centre(c);
    for (int d = 0; d < kStrainDefinitionCount; ++d) {
      if (!strain.computed[d]) continue;
      const CellStrainFields& f = strain.fields[d];
      std::ostringstream row;
      row.precision(17);
      row << strain.time << ',' << strain.step << ',' << strain.reference_time << ',' << name_of(strain.set)
          << ',' << c << ',' << i << ',' << j << ',' << k << ',' << x.x() << ',' << x.y() << ',' << x.z()
          << ',' << field_name(static_cast<StrainDefinition>(d)) << ',' << strain.particles[c];
      cell_columns(row, f, c);
      // The objective stress rates (zero, no_history, without them).
      const CellStressRates* r = rates && rates->computed[d] ? &rates->fields[d] : nullptr;
      row << ',' << static_cast<int>(r ? r->reason[c] : StrainReason::no_history) << ','
          << static_cast<int>(r ? r->green_naghdi_reason[c] : StrainReason::no_history);
      for (const std::vector<Mat3>* t : {r ? &r->jaumann : nullptr, r ? &r->green_naghdi : nullptr,
                                         r ? &r->truesdell : nullptr, r ? &r->oldroyd : nullptr})
        for (int e = 0; e < 9; ++e) row << ',' << (t ? (*t)[c](e / 3, e % 3) : 0.0);
      row << '\n';
      rows += row.str();
    }
  }
  csv_.append(rows);
  flush();
}

void GridStrainRecorder::resume(const std::vector<GridStrainEntry>& entries, long csv_rows) {
  entries_ = entries;
  csv_.resume(csv_rows);
  flush();
}

void GridStrainRecorder::flush() const {
  std::vector<GridXdmfStep> steps;
  for (const GridStrainEntry& e : entries_) {
    GridXdmfStep step{e.file, e.time, e.step, e.grid, {}};
    step.attributes.push_back({"particles", "Scalar", "/cells/particles", 1, "Int", 8});
    for (int d = 0; d < kStrainDefinitionCount; ++d) {
      if (!e.computed[d]) continue;
      const std::string n = field_name(static_cast<StrainDefinition>(d));
      step.attributes.push_back({n + "_ln_J", "Scalar", "/" + n + "/ln_J"});
      step.attributes.push_back(
          {n + "_equivalent_shear_strain", "Scalar", "/" + n + "/equivalent_shear_strain"});
      step.attributes.push_back({n + "_F_valid", "Scalar", "/" + n + "/F_valid", 1, "Int", 4});
      step.attributes.push_back({n + "_F_reason", "Scalar", "/" + n + "/F_reason", 1, "Int", 4});
      step.attributes.push_back({n + "_F", "Tensor", "/" + n + "/F", 9});
      step.attributes.push_back({n + "_increment_equivalent_shear_strain", "Scalar",
                                 "/" + n + "/increment_equivalent_shear_strain"});
      step.attributes.push_back({n + "_L", "Tensor", "/" + n + "/L", 9});
      if (e.rates) {
        step.attributes.push_back({n + "_rate_reason", "Scalar", "/" + n + "/rate_reason", 1, "Int", 4});
        for (const char* rate : {"jaumann_rate", "green_naghdi_rate", "truesdell_rate", "oldroyd_rate"})
          step.attributes.push_back({n + "_" + rate, "Tensor", "/" + n + "/" + rate, 9});
      }
    }
    steps.push_back(std::move(step));
  }
  write_grid_xdmf(folder_ / "grid_strain.xdmf", "grid_strain", steps);
}

void write_compute_grid_strain(const std::filesystem::path& path, const GridStrain& strain,
                               const std::vector<Box>& blocks, std::span<const GlobalId> id,
                               std::span<const int> member) {
  using namespace hdf5;
  const auto n = static_cast<hsize_t>(blocks.size());
  std::vector<double> lo(3 * n), hi(3 * n);
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (int a = 0; a < 3; ++a) {
      lo[3 * b + a] = blocks[b].lo[a];
      hi[3 * b + a] = blocks[b].hi[a];
    }
  std::vector<std::int64_t> ids(id.begin(), id.end());
  std::vector<std::int32_t> block(member.begin(), member.end());
  AtomicFile target(path);
  {
    Handle file(hdf5::create_file(target.temporary_path()), H5Fclose,
                "create " + target.temporary_path().string());
    write_strain_attributes(file, strain);
    {
      Handle g(create_group(file, "blocks"), H5Gclose, "create group blocks");
      write_dataset(g, "lo", lo.data(), n, 3);
      write_dataset(g, "hi", hi.data(), n, 3);
      write_dataset(g, "particles", strain.particles.data(), n, 1);
    }
    {
      Handle g(create_group(file, "sets"), H5Gclose, "create group sets");
      write_dataset(g, "id", ids.data(), ids.size(), 1);
      write_dataset(g, "block", block.data(), block.size(), 1);
    }
    write_definitions(file, strain, nullptr);
    hdf5::flush(file, target.final_path().string());
  }
  target.commit();
}

namespace {
std::string compute_grid_csv_header() {
  std::ostringstream csv;
  csv << "# Upgrain strain per compute grid (MPI block; the blocks depend on the rank count and move with "
         "the load balance). "
      << reason_legend() << ".\ntime,step,reference_time,set,block,lo_x,lo_y,lo_z,hi_x,hi_y,hi_z,definition,"
      << kCellColumns << '\n';
  return csv.str();
}
}  // namespace

ComputeGridStrainRecorder::ComputeGridStrainRecorder(std::filesystem::path folder)
    : folder_(std::move(folder)), csv_(folder_ / "compute_grid_strain.csv", compute_grid_csv_header()) {
  create_folder(folder_ / "compute_grid_strain");
}

void ComputeGridStrainRecorder::record(const GridStrain& strain, const std::vector<Box>& blocks,
                                       std::span<const GlobalId> id, std::span<const int> member) {
  if (strain.particles.size() != blocks.size() || id.size() != member.size())
    throw Error("compute-grid strain: " + std::to_string(strain.particles.size()) + " sets for " +
                std::to_string(blocks.size()) + " blocks, " + std::to_string(id.size()) + " ids for " +
                std::to_string(member.size()) + " members");
  char name[64];
  std::snprintf(name, sizeof name, "compute_grid_strain_%09ld.h5", strain.step);
  write_compute_grid_strain(folder_ / "compute_grid_strain" / name, strain, blocks, id, member);
  std::string rows;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const int c = static_cast<int>(b);
    for (int d = 0; d < kStrainDefinitionCount; ++d) {
      if (!strain.computed[d]) continue;
      std::ostringstream row;
      row.precision(17);
      row << strain.time << ',' << strain.step << ',' << strain.reference_time << ',' << name_of(strain.set)
          << ',' << b;
      for (int a = 0; a < 3; ++a) row << ',' << blocks[b].lo[a];
      for (int a = 0; a < 3; ++a) row << ',' << blocks[b].hi[a];
      row << ',' << field_name(static_cast<StrainDefinition>(d)) << ',' << strain.particles[b];
      cell_columns(row, strain.fields[d], c);
      row << '\n';
      rows += row.str();
    }
  }
  csv_.append(rows);
}

}  // namespace upgrain::upscale
