#include "upscale/grid_fields.h"

#include <hdf5.h>

#include <algorithm>
#include <utility>

#include "dem/core/error.h"
#include "dem/io/grid_stress_output.h"
#include "dem/io/hdf5_util.h"
#include "dem/stress/asymmetry.h"

namespace upgrain::upscale {

namespace {

namespace hdf5 = dem::io::hdf5;

constexpr const char* kComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
constexpr const char* kCounts[4] = {"particles", "internal_contacts", "external_contacts", "wall_contacts"};

std::string list_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "(none)" : s;
}

// HDF5 prints its error stack to stderr on every failed call; our errors say what went
// wrong, so the printing is switched off while a file is read.
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// Reads datasets and attributes of one open file; every error names the file and the
// object.
class Reader {
 public:
  explicit Reader(const std::filesystem::path& path)
      : path_(path), file_(open(path), H5Fclose, "open " + path.string()) {}

  // True when every component of the absolute path `name` exists.
  [[nodiscard]] bool exists(const std::string& name) const {
    std::size_t pos = 0;
    while ((pos = name.find('/', pos + 1)) != std::string::npos)
      if (H5Lexists(file_, name.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
    return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
  }

  // A dataset of `rows` x `cols` values (rows only when cols == 1), converted to `mem_type`.
  template <class T>
  std::vector<T> read(const std::string& name, hid_t mem_type, hsize_t rows, hsize_t cols = 1) const {
    if (!exists(name)) throw Error(where() + "missing dataset " + name);
    hdf5::Handle set(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose,
                     "open dataset " + name + where(true));
    hdf5::Handle space(H5Dget_space(set), H5Sclose, "get the dataspace of " + name + where(true));
    const int rank = H5Sget_simple_extent_ndims(space);
    hsize_t dims[2] = {0, 1};
    if (rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space, dims, nullptr) < 0 || dims[0] != rows ||
        dims[1] != cols)
      throw Error(where() + "dataset " + name + " has shape " + shape(rank, dims) + ", expected " +
                  std::to_string(rows) + (cols == 1 ? "" : " x " + std::to_string(cols)));
    std::vector<T> v(rows * cols);
    if (!v.empty() && H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      throw Error(where() + "cannot read dataset " + name);
    return v;
  }

  [[nodiscard]] double attribute(const char* name) const {
    if (H5Aexists(file_, name) <= 0) throw Error(where() + "missing attribute " + name);
    hdf5::Handle a(H5Aopen(file_, name, H5P_DEFAULT), H5Aclose,
                   std::string("open attribute ") + name + where(true));
    double v = 0.0;
    if (H5Aread(a, H5T_NATIVE_DOUBLE, &v) < 0) throw Error(where() + "cannot read attribute " + name);
    return v;
  }

  // Names of the links in group `name`, by name.
  [[nodiscard]] std::vector<std::string> members(const std::string& name) const {
    if (!exists(name)) throw Error(where() + "missing group " + name);
    hdf5::Handle g(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + name + where(true));
    H5G_info_t info;
    if (H5Gget_info(g, &info) < 0) throw Error(where() + "cannot list group " + name);
    std::vector<std::string> out;
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const ssize_t len = H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
      if (len < 0) throw Error(where() + "cannot list group " + name);
      std::string s(static_cast<std::size_t>(len) + 1, '\0');
      H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, s.data(), s.size(), H5P_DEFAULT);
      s.resize(static_cast<std::size_t>(len));
      out.push_back(std::move(s));
    }
    return out;
  }

 private:
  static hid_t open(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
      throw Error("grid-stress file " + path.string() + ": no such file");
    if (H5Fis_hdf5(path.c_str()) <= 0)
      throw Error("grid-stress file " + path.string() + ": not an HDF5 file");
    return H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  [[nodiscard]] std::string where(bool suffix = false) const {
    return suffix ? " in " + path_.string() : "grid-stress file " + path_.string() + ": ";
  }
  static std::string shape(int rank, const hsize_t* dims) {
    std::string s;
    for (int d = 0; d < rank; ++d) s += (d ? " x " : "") + std::to_string(dims[d]);
    return rank < 1 ? "(scalar)" : s;
  }

  std::filesystem::path path_;
  hdf5::Handle file_;
};

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

GridFields read_grid_fields(const std::filesystem::path& h5_file) {
  QuietHdf5 quiet;
  Reader in(h5_file);
  GridFields g;
  const auto n = in.read<int>("/grid/n", H5T_NATIVE_INT, 3);
  const auto lo = in.read<double>("/grid/lo", H5T_NATIVE_DOUBLE, 3);
  const auto hi = in.read<double>("/grid/hi", H5T_NATIVE_DOUBLE, 3);
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 1)
      throw Error("grid-stress file " + h5_file.string() + ": /grid/n has " + std::to_string(n[d]) +
                  " cells");
    g.n[d] = n[d];
    g.lo[d] = lo[d];
    g.hi[d] = hi[d];
  }
  g.time = in.attribute("time");
  g.step = static_cast<long>(in.attribute("step"));
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
