#include "dem/io/hdf5_util.h"

#include <algorithm>

#include "dem/core/error.h"

namespace upgrain::dem::io::hdf5 {

Handle::Handle(hid_t h, herr_t (*close)(hid_t), const std::string& what) : h_(h), close_(close) {
  if (h_ < 0) throw Error("HDF5: cannot " + what);
}

namespace {
// Object creation properties without modification times, so that a file's bytes depend
// only on its content: the same run on any rank count writes identical files.
hid_t untimed(hid_t property_class) {
  const hid_t p = H5Pcreate(property_class);
  if (p < 0 || H5Pset_obj_track_times(p, false) < 0) throw Error("HDF5: cannot create a property list");
  return p;
}
}  // namespace

void write_dataset(hid_t group, const char* name, const void* data, const DatasetLayout& layout) {
  const hsize_t dims[2] = {layout.rows, layout.cols};
  Handle space(H5Screate_simple(layout.cols == 1 ? 1 : 2, dims, nullptr), H5Sclose, "create a dataspace");
  Handle properties(untimed(H5P_DATASET_CREATE), H5Pclose, "create a property list");
  Handle set(H5Dcreate2(group, name, layout.file_type, space, H5P_DEFAULT, properties, H5P_DEFAULT), H5Dclose,
             std::string("create dataset ") + name);
  if (layout.rows > 0 && H5Dwrite(set, layout.memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw Error(std::string("HDF5: cannot write dataset ") + name);
}

void write_attribute(hid_t obj, const char* name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a dataspace");
  Handle attr(H5Acreate2(obj, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &value);
}

void write_attribute(hid_t obj, const char* name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy a string type");
  H5Tset_size(type, std::max<std::size_t>(value.size(), 1));
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create a dataspace");
  Handle attr(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  H5Awrite(attr, type, value.c_str());
}

void write_attribute(hid_t obj, const char* name, const std::vector<std::string>& values) {
  std::size_t width = 1;
  for (const std::string& v : values) width = std::max(width, v.size());
  std::string packed(width * values.size(), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) packed.replace(i * width, values[i].size(), values[i]);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy a string type");
  H5Tset_size(type, width);
  H5Tset_strpad(type, H5T_STR_NULLPAD);
  const hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose, "create a dataspace");
  Handle attr(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  if (n > 0) H5Awrite(attr, type, packed.data());
}

void write_vectors(hid_t group, const char* name, const std::vector<Vec3>& v) {
  std::vector<double> flat(3 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int d = 0; d < 3; ++d) flat[3 * i + d] = v[i][d];
  write_dataset(group, name, flat.data(), v.size(), 3);
}

void write_tensors(hid_t group, const char* name, const std::vector<Mat3>& t) {
  std::vector<double> flat(9 * t.size());
  for (std::size_t c = 0; c < t.size(); ++c)
    for (int e = 0; e < 9; ++e) flat[9 * c + e] = t[c](e / 3, e % 3);
  write_dataset(group, name, flat.data(), t.size(), 9);
}

hid_t create_group(hid_t parent, const std::string& name) {
  Handle properties(untimed(H5P_GROUP_CREATE), H5Pclose, "create a property list");
  const hid_t g = H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, properties, H5P_DEFAULT);
  if (g < 0) throw Error("HDF5: cannot create group " + name);
  return g;
}

void flush(hid_t file, const std::string& path) {
  if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
    throw Error("cannot write " + path + " (HDF5 flush failed: is the disk full?)");
}

}  // namespace upgrain::dem::io::hdf5
