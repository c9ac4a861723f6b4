#include "upscale/strain/strain_state_file.h"

#include <cstdint>

#include "dem/core/error.h"
#include "dem/io/hdf5_util.h"
#include "dem/io/output_state_file.h"

namespace upgrain::upscale {

namespace {

namespace hdf5 = dem::io::hdf5;
using hdf5::Handle;
using hdf5::write_attribute;
using hdf5::write_dataset;

void write_grid(hid_t g, const dem::RegularGrid& grid) {
  double nine[9];
  dem::io::put_grid(grid, nine);
  write_dataset(g, "grid", nine, 9);
}
dem::RegularGrid read_grid(const Reader& in, const std::string& group) {
  const std::vector<double> nine = in.read<double>(group + "/grid", H5T_NATIVE_DOUBLE, 9);
  return dem::io::get_grid(nine.data(), in);
}

void write_reasons(hid_t g, const char* name, const std::vector<StrainReason>& r) {
  std::vector<std::int32_t> code(r.size());
  for (std::size_t c = 0; c < r.size(); ++c) code[c] = static_cast<std::int32_t>(r[c]);
  write_dataset(g, name, code.data(), code.size());
}
std::vector<StrainReason> read_reasons(const Reader& in, const std::string& name, std::size_t cells) {
  std::vector<StrainReason> out;
  for (std::int32_t c : in.read<std::int32_t>(name, H5T_NATIVE_INT32, cells)) {
    if (c < 0 || c >= kStrainReasonCount) throw Error(in.where() + name + " holds an unknown reason code");
    out.push_back(static_cast<StrainReason>(c));
  }
  return out;
}

}  // namespace

void write_strain_reference(hid_t parent, const std::string& group, const StrainReference& r) {
  Handle g(hdf5::create_group(parent, group), H5Gclose, "create group " + group);
  write_attribute(g, "time", r.time);
  write_attribute(g, "step", static_cast<double>(r.step));
  write_attribute(g, "cells", static_cast<double>(r.cells));
  write_grid(g, r.grid);
  write_dataset(g, "id", r.id.data(), r.id.size());
  hdf5::write_vectors(g, "x", r.x);
  std::vector<std::int32_t> cell(r.cell.begin(), r.cell.end());
  write_dataset(g, "cell", cell.data(), cell.size());
  // A periodic cell's image counters at t0; a bounded box's references keep their layout.
  if (!r.image.empty()) {
    std::vector<std::int32_t> image(3 * r.image.size());
    for (std::size_t i = 0; i < r.image.size(); ++i)
      for (int d = 0; d < 3; ++d) image[3 * i + d] = r.image[i][d];
    write_dataset(g, "image", image.data(), r.image.size(), 3);
  }
  if (!r.cell_matrix.isZero()) write_dataset(g, "cell_matrix", r.cell_matrix.data(), 9);
}

StrainReference read_strain_reference(const Reader& in, const std::string& group) {
  StrainReference r;
  r.time = in.attribute("time", group);
  r.step = in.whole_attribute("step", group);
  r.cells = static_cast<int>(in.whole_attribute("cells", group, 0, 1 << 30));
  r.grid = read_grid(in, group);
  r.id = in.read_all<std::int64_t>(group + "/id");
  r.x = in.read_vectors(group + "/x");
  const std::vector<std::int32_t> cell =
      in.read<std::int32_t>(group + "/cell", H5T_NATIVE_INT32, r.id.size());
  r.cell.assign(cell.begin(), cell.end());
  if (r.x.size() != r.id.size()) throw Error(in.where() + group + ": positions and ids differ in count");
  if (in.exists(group + "/image")) {
    const std::vector<std::int32_t> image =
        in.read<std::int32_t>(group + "/image", H5T_NATIVE_INT32, r.id.size(), 3);
    for (std::size_t i = 0; i < r.id.size(); ++i)
      r.image.push_back({image[3 * i], image[3 * i + 1], image[3 * i + 2]});
  }
  if (in.exists(group + "/cell_matrix")) {
    const std::vector<double> h = in.read<double>(group + "/cell_matrix", H5T_NATIVE_DOUBLE, 9);
    r.cell_matrix = Eigen::Map<const Mat3>(h.data());
  }
  return r;
}

void write_previous_strain(hid_t parent, const std::string& group, const GridStrain& s) {
  Handle g(hdf5::create_group(parent, group), H5Gclose, "create group " + group);
  write_attribute(g, "set", static_cast<double>(s.set));
  write_attribute(g, "reference_time", s.reference_time);
  write_attribute(g, "reference_step", static_cast<double>(s.reference_step));
  write_attribute(g, "time", s.time);
  write_attribute(g, "step", static_cast<double>(s.step));
  write_attribute(g, "untracked", static_cast<double>(s.untracked));
  write_grid(g, s.grid);
  write_dataset(g, "particles", s.particles.data(), s.particles.size());
  for (int d = 0; d < kStrainDefinitionCount; ++d) {
    if (!s.computed[d]) continue;
    const std::string name = field_name(static_cast<StrainDefinition>(d));
    Handle def(hdf5::create_group(g, name), H5Gclose, "create group " + name);
    hdf5::write_tensors(def, "F", s.fields[d].deformation_gradient);
    write_reasons(def, "F_reason", s.fields[d].f_reason);
  }
}

GridStrain read_previous_strain(const Reader& in, const std::string& group) {
  GridStrain s;
  s.set = static_cast<StrainSet>(in.whole_attribute("set", group, 0, 1));
  s.reference_time = in.attribute("reference_time", group);
  s.reference_step = in.whole_attribute("reference_step", group);
  s.time = in.attribute("time", group);
  s.step = in.whole_attribute("step", group);
  s.untracked = in.whole_attribute("untracked", group);
  s.grid = read_grid(in, group);
  s.particles = in.read_all<std::int64_t>(group + "/particles");
  const int cells = static_cast<int>(s.particles.size());
  for (int d = 0; d < kStrainDefinitionCount; ++d) {
    const std::string def = group + "/" + field_name(static_cast<StrainDefinition>(d));
    if (!in.exists(def)) continue;
    s.computed[d] = true;
    s.fields[d].resize(cells);
    s.fields[d].deformation_gradient = in.read_tensors(def + "/F");
    s.fields[d].f_reason = read_reasons(in, def + "/F_reason", static_cast<std::size_t>(cells));
    if (static_cast<int>(s.fields[d].deformation_gradient.size()) != cells)
      throw Error(in.where() + def + "/F does not hold one tensor per cell");
  }
  return s;
}

void write_rate_history(hid_t parent, const std::string& group, const StressRateHistory& h) {
  Handle g(hdf5::create_group(parent, group), H5Gclose, "create group " + group);
  write_attribute(g, "formula", static_cast<double>(h.formula()));
  write_attribute(g, "outputs", static_cast<double>(h.outputs().size()));
  int k = 0;
  for (const StressRateHistory::Output& o : h.outputs()) {
    const std::string name = "output_" + std::to_string(k++);
    Handle out(hdf5::create_group(g, name), H5Gclose, "create group " + name);
    write_attribute(out, "time", o.time);
    hdf5::write_tensors(out, "stress", o.stress);
    for (int d = 0; d < kStrainDefinitionCount; ++d) {
      const std::string def = field_name(static_cast<StrainDefinition>(d));
      Handle dg(hdf5::create_group(out, def), H5Gclose, "create group " + def);
      hdf5::write_tensors(dg, "rotation", o.rotation[d]);
      write_reasons(dg, "F_reason", o.f_reason[d]);
    }
  }
}

StressRateHistory read_rate_history(const Reader& in, const std::string& group, dem::StressFormula formula) {
  if (in.whole_attribute("formula", group, 0, dem::kStressFormulaCount - 1) != static_cast<int>(formula))
    throw Error(in.where() + "the stress rates were kept for another stress formula (Strain/rate formula)");
  StressRateHistory h(formula);
  std::deque<StressRateHistory::Output> outputs;
  const int n = static_cast<int>(in.whole_attribute("outputs", group, 0, 1 << 20));
  for (int k = 0; k < n; ++k) {
    const std::string name = group + "/output_" + std::to_string(k);
    StressRateHistory::Output o;
    o.time = in.attribute("time", name);
    o.stress = in.read_tensors(name + "/stress");
    for (int d = 0; d < kStrainDefinitionCount; ++d) {
      const std::string def = name + "/" + field_name(static_cast<StrainDefinition>(d));
      o.rotation[d] = in.read_tensors(def + "/rotation");
      o.f_reason[d] = read_reasons(in, def + "/F_reason", in.rows(def + "/F_reason"));
    }
    outputs.push_back(std::move(o));
  }
  h.restore(std::move(outputs));
  return h;
}

void write_strain_list(hid_t parent, const std::string& group, const std::vector<GridStrainEntry>& list) {
  Handle g(hdf5::create_group(parent, group), H5Gclose, "create group " + group);
  std::vector<std::string> files;
  std::vector<double> values;
  for (const GridStrainEntry& e : list) {
    files.push_back(e.file);
    double row[14] = {e.time, static_cast<double>(e.step)};
    dem::io::put_grid(e.grid, row + 2);
    row[11] = e.computed[0] ? 1.0 : 0.0;
    row[12] = e.computed[1] ? 1.0 : 0.0;
    row[13] = e.rates ? 1.0 : 0.0;
    values.insert(values.end(), row, row + 14);
  }
  write_attribute(g, "files", files);
  write_dataset(g, "values", values.data(), files.size(), 14);
}

std::vector<GridStrainEntry> read_strain_list(const Reader& in, const std::string& group) {
  const std::vector<std::string> files = in.text_list_attribute("files", group);
  const std::vector<double> v = in.read<double>(group + "/values", H5T_NATIVE_DOUBLE, files.size(), 14);
  std::vector<GridStrainEntry> out;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const double* row = v.data() + 14 * k;
    GridStrainEntry e;
    e.file = files[k];
    e.time = row[0];
    e.step = in.whole(row[1], group + " step");
    e.grid = dem::io::get_grid(row + 2, in);
    e.computed = {row[11] != 0.0, row[12] != 0.0};
    e.rates = row[13] != 0.0;
    out.push_back(e);
  }
  return out;
}

}  // namespace upgrain::upscale
