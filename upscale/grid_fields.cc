#include "upscale/grid_fields.h"

#include <hdf5.h>

#include <algorithm>
#include <utility>

#include "dem/core/error.h"
#include "dem/io/grid_stress_output.h"
#include "dem/io/hdf5_reader.h"
#include "dem/io/hdf5_util.h"
#include "dem/stress/asymmetry.h"

namespace upgrain::upscale {

namespace {

using dem::io::hdf5::QuietHdf5;
using dem::io::hdf5::Reader;

constexpr const char* kComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
constexpr const char* kCounts[4] = {"particles", "internal_contacts", "external_contacts", "wall_contacts"};

std::string list_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "(none)" : s;
}

// Order of the formula groups in a file: the known ones as dem::StressFormula, then others.
int formula_rank(const std::string& group) {
  for (int k = 0; k < dem::kStressFormulaCount; ++k)
    if (dem::io::field_name(static_cast<dem::StressFormula>(k)) == group) return k;
  return dem::kStressFormulaCount;
}

}  // namespace

void GridFields::add(std::string name, std::vector<double> v) {
  if (std::find(names.begin(), names.end(), name) != names.end())
    throw Error("grid field " + name + " is already there");
  if (v.size() != static_cast<std::size_t>(num_cells()))
    throw Error("grid field " + name + " has " + std::to_string(v.size()) + " values, the grid " +
                std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) + " has " +
                std::to_string(num_cells()) + " cells");
  names.push_back(std::move(name));
  values.push_back(std::move(v));
}

const std::vector<double>& GridFields::operator[](const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw Error("no grid field " + name + "; there are: " + list_names(names));
  return values[static_cast<std::size_t>(it - names.begin())];
}

GridFields grid_fields_from_stress(const dem::RegularGrid& grid, const dem::GridStress& stress,
                                   const std::vector<dem::StressFormula>& formulas) {
  GridFields g;
  for (int d = 0; d < 3; ++d) {
    g.n[d] = grid.n[d];
    g.lo[d] = grid.lo[d];
    g.hi[d] = grid.hi[d];
  }
  const auto cells = static_cast<std::size_t>(g.num_cells());
  for (dem::StressFormula f : formulas) {
    const std::string base = dem::io::field_name(f);
    const std::vector<dem::Mat3>& sigma = stress[f];
    if (sigma.size() != cells)
      throw Error("grid stress " + base + " has " + std::to_string(sigma.size()) + " cells, the grid has " +
                  std::to_string(cells));
    for (int e = 0; e < 9; ++e) {
      std::vector<double> v(cells);
      for (std::size_t c = 0; c < cells; ++c) v[c] = sigma[c](e / 3, e % 3);
      g.add(base + "_s_" + kComponents[e], std::move(v));
    }
    std::vector<double> rai(cells);
    for (std::size_t c = 0; c < cells; ++c) rai[c] = dem::relative_asymmetry_index(sigma[c]);
    g.add(base + "_rai", std::move(rai));
  }
  const std::vector<long>* counts[4] = {&stress.particles, &stress.internal_contacts,
                                        &stress.external_contacts, &stress.wall_contacts};
  for (int k = 0; k < 4; ++k) g.add(kCounts[k], std::vector<double>(counts[k]->begin(), counts[k]->end()));
  g.add("solid_fraction", stress.solid_fraction);
  return g;
}

GridFields read_grid_header(const Reader& in) {
  GridFields g;
  const auto n = in.read<int>("/grid/n", H5T_NATIVE_INT, 3);
  const auto lo = in.read<double>("/grid/lo", H5T_NATIVE_DOUBLE, 3);
  const auto hi = in.read<double>("/grid/hi", H5T_NATIVE_DOUBLE, 3);
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 1) throw Error(in.where() + "/grid/n has " + std::to_string(n[d]) + " cells");
    g.n[d] = n[d];
    g.lo[d] = lo[d];
    g.hi[d] = hi[d];
  }
  g.time = in.attribute("time");
  g.step = static_cast<long>(in.attribute("step"));
  return g;
}

GridFields read_grid_fields(const std::filesystem::path& h5_file) {
  QuietHdf5 quiet;
  Reader in(h5_file, "grid-stress file");
  GridFields g = read_grid_header(in);
  const auto cells = static_cast<hsize_t>(g.num_cells());

  std::vector<std::string> groups = in.members("/stress");
  std::stable_sort(groups.begin(), groups.end(), [](const std::string& a, const std::string& b) {
    return formula_rank(a) < formula_rank(b);
  });
  for (const std::string& f : groups) {
    const auto tensor = in.read<double>("/stress/" + f + "/tensor", H5T_NATIVE_DOUBLE, cells, 9);
    for (int e = 0; e < 9; ++e) {
      std::vector<double> v(cells);
      for (hsize_t c = 0; c < cells; ++c) v[c] = tensor[9 * c + e];
      g.add(f + "_s_" + kComponents[e], std::move(v));
    }
    g.add(f + "_rai", in.read<double>("/stress/" + f + "/rai", H5T_NATIVE_DOUBLE, cells));
  }
  // Counts are stored as 64-bit integers; every count below 2^53 converts exactly.
  for (const char* c : kCounts)
    g.add(c, in.read<double>(std::string("/cells/") + c, H5T_NATIVE_DOUBLE, cells));
  g.add("solid_fraction", in.read<double>("/cells/solid_fraction", H5T_NATIVE_DOUBLE, cells));
  return g;
}

}  // namespace upgrain::upscale
