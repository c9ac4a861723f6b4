#include "dem/io/hdf5_util.h"

#include <algorithm>
#include <optional>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/parallel/exchange.h"

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

hid_t create_shared_file(MPI_Comm comm, const std::filesystem::path& path) {
  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create a file access property list");
  if (H5Pset_fapl_mpio(access, comm, MPI_INFO_NULL) < 0 || H5Pset_all_coll_metadata_ops(access, true) < 0 ||
      H5Pset_coll_metadata_write(access, true) < 0)
    throw Error("HDF5: cannot select the MPI-IO file driver");
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access);
  if (f < 0) throw Error("HDF5: cannot create " + path.string());
  return f;
}

void write_shared_file(MPI_Comm comm, const std::filesystem::path& path, std::size_t bytes,
                       const std::function<void(hid_t)>& fill) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::optional<AtomicFile> target;  // rank 0
  std::string temporary, error;
  if (rank == 0) {
    try {
      target.emplace(path);
      reserve_bytes(target->temporary_path(), bytes, path.string());
      temporary = target->temporary_path().string();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  throw_if_any(comm, error);
  int length = static_cast<int>(temporary.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  temporary.resize(static_cast<std::size_t>(length));
  MPI_Bcast(temporary.data(), length, MPI_CHAR, 0, comm);
  {
    Handle file(create_shared_file(comm, temporary), H5Fclose, "create " + path.string());
    fill(file);
    // Every cached piece of metadata to the file before it is closed, and a failure seen by all.
    int flushed = H5Fflush(file, H5F_SCOPE_GLOBAL) >= 0 ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &flushed, 1, MPI_INT, MPI_MIN, comm);
    if (flushed == 0) throw Error("HDF5: cannot write " + path.string());
  }
  if (rank == 0) {
    try {
      sync_reserved(temporary, bytes, path.string());
      target->commit();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  throw_if_any(comm, error);
}

void write_rows(MPI_Comm comm, hid_t group, const char* name, const void* data, const DatasetLayout& layout,
                hsize_t first, hsize_t count) {
  write_row_blocks(comm, group, name, data, layout, {RowBlock{first, count}});
}

void write_row_blocks(MPI_Comm comm, hid_t group, const char* name, const void* data,
                      const DatasetLayout& layout, const std::vector<RowBlock>& blocks) {
  const int rank = layout.cols == 1 ? 1 : 2;
  const hsize_t dims[2] = {layout.rows, layout.cols};
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose, "create a dataspace");
  Handle properties(untimed(H5P_DATASET_CREATE), H5Pclose, "create a property list");
  // Parallel HDF5 allocates a data set when it is made; every row is then written once, so
  // no fill value is written before.
  if (H5Pset_alloc_time(properties, H5D_ALLOC_TIME_EARLY) < 0 ||
      H5Pset_fill_time(properties, H5D_FILL_TIME_NEVER) < 0)
    throw Error("HDF5: cannot set the allocation of dataset " + std::string(name));
  Handle set(H5Dcreate2(group, name, layout.file_type, space, H5P_DEFAULT, properties, H5P_DEFAULT), H5Dclose,
             std::string("create dataset ") + name);
  // A data set of no rows (a snapshot before a pour's first grain) is complete when made: every
  // rank knows the row count, so all skip the write together (a collective write of nothing
  // fails in MPI-IO).
  if (layout.rows == 0) return;
  hsize_t count = 0;
  for (const RowBlock& b : blocks) count += b.count;
  const hsize_t mine[2] = {count, layout.cols};
  Handle memory(H5Screate_simple(rank, count > 0 ? mine : dims, nullptr), H5Sclose, "create a dataspace");
  bool ok = true;
  if (count > 0) {
    // The union of the blocks; the memory's rows go to it in the file's row order.
    bool first_block = true;
    for (const RowBlock& b : blocks) {
      if (b.count == 0) continue;
      const hsize_t start[2] = {b.first, 0};
      const hsize_t size[2] = {b.count, layout.cols};
      ok = ok && H5Sselect_hyperslab(space, first_block ? H5S_SELECT_SET : H5S_SELECT_OR, start, nullptr,
                                     size, nullptr) >= 0;
      first_block = false;
    }
  } else {
    ok = H5Sselect_none(space) >= 0 && H5Sselect_none(memory) >= 0;
  }
  Handle transfer(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "create a transfer property list");
  ok = ok && H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE) >= 0;
  // Every rank takes part in the collective write, also one whose selection failed (with none).
  if (!ok) {
    H5Sselect_none(space);
    H5Sselect_none(memory);
  }
  // HDF5 refuses a null buffer even for an empty selection.
  const double nothing = 0.0;
  ok = H5Dwrite(set, layout.memory_type, memory, space, transfer, data != nullptr ? data : &nothing) >= 0 &&
       ok;
  int all = ok ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_MIN, comm);
  if (all == 0) throw Error(std::string("HDF5: cannot write dataset ") + name);
}

hid_t create_file(const std::filesystem::path& path, hsize_t user_block) {
  // The image grows by 1 MiB at a time; nothing is written behind it.
  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create a file access property list");
  if (H5Pset_fapl_core(access, std::size_t{1} << 20, false) < 0)
    throw Error("HDF5: cannot select the in-memory file driver");
  Handle creation(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "create a file creation property list");
  if (user_block > 0 && H5Pset_userblock(creation, user_block) < 0)
    throw Error("HDF5: cannot reserve a user block of " + std::to_string(user_block) + " bytes");
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation, access);
  if (f < 0) throw Error("HDF5: cannot create " + path.string());
  return f;
}

std::vector<unsigned char> file_image(hid_t file) {
  // Every cached object's metadata into the image first (the image alone leaves out what open
  // groups and datasets still hold).
  if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0) throw Error("HDF5: cannot flush a file built in memory");
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  std::vector<unsigned char> image(size > 0 ? static_cast<std::size_t>(size) : 0);
  if (size <= 0 || H5Fget_file_image(file, image.data(), image.size()) != size)
    throw Error("HDF5: cannot take the image of a file built in memory");
  return image;
}

void flush(hid_t file, const std::string& path) {
  const ssize_t length = H5Fget_name(file, nullptr, 0);
  std::string name(length > 0 ? static_cast<std::size_t>(length) : 0, '\0');
  if (length <= 0 || H5Fget_name(file, name.data(), name.size() + 1) != length)
    throw Error("HDF5: cannot name the file of " + path);
  const std::vector<unsigned char> image = file_image(file);
  write_bytes(name, image.data(), image.size(), path);
}

}  // namespace upgrain::dem::io::hdf5
