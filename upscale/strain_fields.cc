#include "upscale/strain_fields.h"

#include <string>
#include <utility>
#include <vector>

#include "dem/io/hdf5_reader.h"
#include "upscale/strain/grid_strain_output.h"

namespace upgrain::upscale {

namespace {
constexpr const char* kComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};

void add_tensor(GridFields& g, const std::string& name, const std::vector<dem::Mat3>& t) {
  for (int e = 0; e < 9; ++e) {
    std::vector<double> v(t.size());
    for (std::size_t c = 0; c < t.size(); ++c) v[c] = t[c](e / 3, e % 3);
    g.add(name + "_" + kComponents[e], std::move(v));
  }
}
}  // namespace

GridFields grid_fields_from_strain(const upscale::GridStrain& strain) {
  GridFields g;
  for (int d = 0; d < 3; ++d) {
    g.n[d] = strain.grid.n[d];
    g.lo[d] = strain.grid.lo[d];
    g.hi[d] = strain.grid.hi[d];
  }
  g.time = strain.time;
  g.step = strain.step;
  for (int d = 0; d < upscale::kStrainDefinitionCount; ++d) {
    if (!strain.computed[d]) continue;
    const upscale::CellStrainFields& f = strain.fields[d];
    const std::string base = field_name(static_cast<StrainDefinition>(d));
    g.add(base + "_ln_J", f.log_jacobian);
    g.add(base + "_J", f.jacobian);
    g.add(base + "_equivalent_shear_strain", f.equivalent_shear_strain);
    g.add(base + "_equivalent_shear_rate", f.equivalent_shear_rate);
    g.add(base + "_increment_equivalent_shear_strain", f.increment_equivalent_shear_strain);
    std::vector<double> valid(f.f_reason.size()), reason(f.f_reason.size());
    for (std::size_t c = 0; c < f.f_reason.size(); ++c) {
      valid[c] = f.f_reason[c] == upscale::StrainReason::valid ? 1.0 : 0.0;
      reason[c] = static_cast<double>(f.f_reason[c]);
    }
    g.add(base + "_F_valid", std::move(valid));
    g.add(base + "_F_reason", std::move(reason));
    add_tensor(g, base + "_F", f.deformation_gradient);
    add_tensor(g, base + "_hencky", f.hencky);
  }
  g.add("particles", std::vector<double>(strain.particles.begin(), strain.particles.end()));
  return g;
}

GridFields read_strain_fields(const std::filesystem::path& h5_file) {
  dem::io::hdf5::QuietHdf5 quiet;
  dem::io::hdf5::Reader in(h5_file, "grid-strain file");
  GridFields g = read_grid_header(in);
  const auto cells = static_cast<hsize_t>(g.num_cells());
  for (int d = 0; d < upscale::kStrainDefinitionCount; ++d) {
    const std::string base = field_name(static_cast<StrainDefinition>(d));
    const std::string group = "/" + base + "/";
    if (!in.exists("/" + base)) continue;
    for (const char* f : {"ln_J", "J", "equivalent_shear_strain", "equivalent_shear_rate",
                          "increment_equivalent_shear_strain", "F_valid", "F_reason"})
      g.add(base + "_" + f, in.read<double>(group + f, H5T_NATIVE_DOUBLE, cells));  // int32 -> double exactly
    for (const char* t : {"F", "hencky"}) {
      const auto flat = in.read<double>(group + t, H5T_NATIVE_DOUBLE, cells, 9);
      for (int e = 0; e < 9; ++e) {
        std::vector<double> v(cells);
        for (hsize_t c = 0; c < cells; ++c) v[c] = flat[9 * c + e];
        g.add(base + "_" + t + "_" + kComponents[e], std::move(v));
      }
    }
  }
  g.add("particles", in.read<double>("/cells/particles", H5T_NATIVE_DOUBLE, cells));
  return g;
}

}  // namespace upgrain::upscale
