#pragma once
// Reading the HDF5 files Upgrain writes (grid stress and strain for the upscaling,
// checkpoints for a restart): an open file whose every error names the file, its kind and the
// object.
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dem/core/error.h"
#include "dem/io/file_kind.h"
#include "dem/io/hdf5_util.h"

namespace upgrain::dem::io::hdf5 {

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
  // `kind` names the file in errors, e.g. "grid-stress file".
  Reader(const std::filesystem::path& path, std::string kind)
      : path_(path), kind_(std::move(kind)), file_(open(path, kind_), H5Fclose, "open " + path.string()) {}

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
    Handle set(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name + where(true));
    Handle space(H5Dget_space(set), H5Sclose, "get the dataspace of " + name + where(true));
    const int rank = H5Sget_simple_extent_ndims(space);
    hsize_t dims[2] = {0, 1};
    if (rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space, dims, nullptr) < 0 || dims[0] != rows ||
        dims[1] != cols)
      throw Error(where() + "dataset " + name + " has shape " + shape(rank, dims) + ", expected " +
                  std::to_string(rows) + (cols == 1 ? "" : " x " + std::to_string(cols)));
    // The data must be in the file before memory is taken for it: a corrupt shape could ask
    // for more than the machine has.
    Handle type(H5Dget_type(set), H5Tclose, "get the type of " + name + where(true));
    if (!holds(H5Dget_storage_size(set), rows, cols * H5Tget_size(type)))
      throw Error(where() + "dataset " + name + " is shorter than its shape (" + shape(rank, dims) + ")");
    std::vector<T> v(rows * cols);
    if (!v.empty() && H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
      throw Error(where() + "cannot read dataset " + name);
    return v;
  }

  // The rows of a 1-D or 2-D dataset (0 when it is missing).
  [[nodiscard]] hsize_t rows(const std::string& name) const {
    if (!exists(name)) return 0;
    Handle set(H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name + where(true));
    Handle space(H5Dget_space(set), H5Sclose, "get the dataspace of " + name + where(true));
    hsize_t dims[2] = {0, 1};
    if (H5Sget_simple_extent_dims(space, dims, nullptr) < 0) throw Error(where() + "cannot size " + name);
    return dims[0];
  }
  // A dataset of T (ElementType, hdf5_util.h) with `cols` columns and as many rows as it has;
  // empty when it is missing and `optional`.
  template <class T>
  std::vector<T> read_all(const std::string& name, hsize_t cols = 1, bool optional = false) const {
    if (optional && !exists(name)) return {};
    return read<T>(name, ElementType<T>::memory(), rows(name), cols);
  }

  // Fields of vectors and tensors (hdf5_util.h: rows of 3 and 9 doubles).
  [[nodiscard]] std::vector<Vec3> read_vectors(const std::string& name, bool optional = false) const {
    const std::vector<double> flat = read_all<double>(name, 3, optional);
    std::vector<Vec3> v(flat.size() / 3);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
    return v;
  }
  [[nodiscard]] std::vector<Mat3> read_tensors(const std::string& name, bool optional = false) const {
    const std::vector<double> flat = read_all<double>(name, 9, optional);
    std::vector<Mat3> t(flat.size() / 9);
    for (std::size_t c = 0; c < t.size(); ++c)
      for (int e = 0; e < 9; ++e) t[c](e / 3, e % 3) = flat[9 * c + e];
    return t;
  }
  // A list of strings written by write_attribute (fixed length, null padded).
  [[nodiscard]] std::vector<std::string> text_list_attribute(const char* name,
                                                             const std::string& object = "/") const {
    Handle a = open_attribute(name, object);
    Handle type(H5Aget_type(a), H5Tclose, std::string("type of attribute ") + name + where(true));
    Handle space(H5Aget_space(a), H5Sclose, std::string("space of attribute ") + name + where(true));
    hsize_t n = 0;
    if (H5Sget_simple_extent_ndims(space) != 1 || H5Sget_simple_extent_dims(space, &n, nullptr) < 0 ||
        H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) > 0)
      throw Error(where() + "attribute " + name + " is not a list of text");
    const std::size_t width = H5Tget_size(type);
    if (!holds(H5Aget_storage_size(a), n, width))
      throw Error(where() + "attribute " + name + " is cut short");
    std::string packed(width * n, '\0');
    if (n > 0 && H5Aread(a, type, packed.data()) < 0) throw Error(where() + "cannot read attribute " + name);
    std::vector<std::string> out(n);
    for (hsize_t i = 0; i < n; ++i) {
      out[i] = packed.substr(i * width, width);
      out[i].resize(std::strlen(out[i].c_str()));
    }
    return out;
  }

  // A number of the file that must be whole and within [lo, hi] (a count, a step, an index, an
  // enumerator): one that is not finite, not whole or out of range is an error naming `what`
  // (converting it would be undefined behaviour).
  static constexpr double kLargestWhole = 9007199254740992.0;  // 2^53
  [[nodiscard]] long whole(double v, const std::string& what, double lo = -kLargestWhole,
                           double hi = kLargestWhole) const {
    if (!(v >= lo && v <= hi) || v != std::floor(v)) {
      std::ostringstream m;
      m.precision(17);
      m << where() << what << " is " << v << ", not a whole number in [" << lo << ", " << hi << "]";
      throw Error(m.str());
    }
    return static_cast<long>(v);
  }
  [[nodiscard]] long whole_attribute(const char* name, const std::string& object = "/",
                                     double lo = -kLargestWhole, double hi = kLargestWhole) const {
    return whole(attribute(name, object), std::string("attribute ") + name + " of " + object, lo, hi);
  }

  // A scalar attribute of the file, or of the group or dataset at `object`.
  [[nodiscard]] double attribute(const char* name, const std::string& object = "/") const {
    Handle a = open_attribute(name, object);
    double v = 0.0;
    if (H5Aread(a, H5T_NATIVE_DOUBLE, &v) < 0) throw Error(where() + "cannot read attribute " + name);
    return v;
  }
  // A string attribute (fixed or variable length).
  [[nodiscard]] std::string text_attribute(const char* name, const std::string& object = "/") const {
    Handle a = open_attribute(name, object);
    Handle type(H5Aget_type(a), H5Tclose, std::string("type of attribute ") + name + where(true));
    if (H5Tget_class(type) != H5T_STRING) throw Error(where() + "attribute " + name + " is not text");
    if (H5Tis_variable_str(type) > 0) {
      char* text = nullptr;
      Handle memory(H5Tcopy(H5T_C_S1), H5Tclose, "copy a string type");
      H5Tset_size(memory, H5T_VARIABLE);
      if (H5Aread(a, memory, &text) < 0) throw Error(where() + "cannot read attribute " + name);
      std::string out = text ? text : "";
      H5free_memory(text);
      return out;
    }
    const std::size_t size = H5Tget_size(type);
    std::string out(size, '\0');
    if (H5Aread(a, type, out.data()) < 0) throw Error(where() + "cannot read attribute " + name);
    out.resize(std::strlen(out.c_str()));
    return out;
  }
  [[nodiscard]] bool has_attribute(const char* name, const std::string& object = "/") const {
    if (object != "/" && !exists(object)) return false;
    return H5Aexists_by_name(file_, object.c_str(), name, H5P_DEFAULT) > 0;
  }

  // "<kind> <path>: " to start an error message, or " in <path>" to end one.
  [[nodiscard]] std::string where(bool suffix = false) const {
    return suffix ? " in " + path_.string() : kind_ + " " + path_.string() + ": ";
  }

  // Names of the links in group `name`, by name.
  [[nodiscard]] std::vector<std::string> members(const std::string& name) const {
    if (!exists(name)) throw Error(where() + "missing group " + name);
    Handle g(H5Gopen2(file_, name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + name + where(true));
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
  Handle open_attribute(const char* name, const std::string& object) const {
    if (!has_attribute(name, object)) throw Error(where() + "missing attribute " + name + " of " + object);
    return Handle(H5Aopen_by_name(file_, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                  std::string("open attribute ") + name + where(true));
  }
  static hid_t open(const std::filesystem::path& path, const std::string& kind) {
    if (const PathKind k = path_kind(path.string()); !k.regular())
      throw Error(kind + " " + path.string() + ": " +
                  (!k.exists ? (k.description == "does not exist" ? "no such file" : k.description)
                             : "is " + k.description + ", not a file"));
    // The probe of a file that is not HDF5 fails inside the library, which prints its error
    // stack unless told not to; the message below says what happened.
    QuietHdf5 quiet;
    if (H5Fis_hdf5(path.c_str()) <= 0) throw Error(kind + " " + path.string() + ": not an HDF5 file");
    return H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  // Whether `stored` bytes hold `count` elements of `size` bytes (without overflow).
  static bool holds(hsize_t stored, hsize_t count, std::size_t size) {
    return size > 0 && count <= stored / size;
  }
  static std::string shape(int rank, const hsize_t* dims) {
    std::string s;
    for (int d = 0; d < rank; ++d) s += (d ? " x " : "") + std::to_string(dims[d]);
    return rank < 1 ? "(scalar)" : s;
  }

  std::filesystem::path path_;
  std::string kind_;
  Handle file_;
};

}  // namespace upgrain::dem::io::hdf5
