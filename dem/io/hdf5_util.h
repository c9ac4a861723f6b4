#pragma once
// Small RAII and write helpers over the HDF5 C API, shared by the snapshot and grid-stress
// writers. Errors become upgrain::Error naming what could not be done.
#include <hdf5.h>
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include <vector>
#include "dem/core/types.h"

namespace upgrain::dem::io::hdf5 {

// Closes an HDF5 handle when it goes out of scope.
class Handle {
 public:
  Handle(hid_t h, herr_t (*close)(hid_t), const std::string& what);
  ~Handle() { close_(h_); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  operator hid_t() const { return h_; }  // NOLINT(google-explicit-constructor)

 private:
  hid_t h_;
  herr_t (*close_)(hid_t);
};

// The memory type and the (little-endian) file type of an element type written.
template <class T>
struct ElementType;
template <>
struct ElementType<double> {
  static hid_t memory() { return H5T_NATIVE_DOUBLE; }
  static hid_t file() { return H5T_IEEE_F64LE; }
};
template <>
struct ElementType<std::int32_t> {
  static hid_t memory() { return H5T_NATIVE_INT32; }
  static hid_t file() { return H5T_STD_I32LE; }
};
template <>
struct ElementType<std::uint8_t> {
  static hid_t memory() { return H5T_NATIVE_UINT8; }
  static hid_t file() { return H5T_STD_U8LE; }
};
template <>
struct ElementType<std::int64_t> {
  static hid_t memory() { return H5T_NATIVE_INT64; }
  static hid_t file() { return H5T_STD_I64LE; }
};

// What a data set holds: its element types and its rows x cols shape (1-D when cols == 1).
struct DatasetLayout {
  hid_t memory_type;
  hid_t file_type;
  hsize_t rows;
  hsize_t cols;
};
void write_dataset(hid_t group, const char* name, const void* data, const DatasetLayout& layout);

// A rows x cols data set of T (1-D when cols == 1).
template <class T>
void write_dataset(hid_t group, const char* name, const T* data, hsize_t rows, hsize_t cols = 1) {
  write_dataset(group, name, static_cast<const void*>(data),
                DatasetLayout{ElementType<T>::memory(), ElementType<T>::file(), rows, cols});
}
void write_attribute(hid_t obj, const char* name, double value);
void write_attribute(hid_t obj, const char* name, const std::string& value);
// A 1-D attribute of fixed-length strings (each padded to the longest).
void write_attribute(hid_t obj, const char* name, const std::vector<std::string>& values);
hid_t create_group(hid_t parent, const std::string& name);
// Fields of vectors and tensors as rows of 3 and 9 doubles (tensors row-major, T_ij at 3 i + j).
void write_vectors(hid_t group, const char* name, const std::vector<Vec3>& v);
void write_tensors(hid_t group, const char* name, const std::vector<Mat3>& t);
// A new file at `path` (an AtomicFile's temporary name) that every rank of `comm` writes its
// share of (HDF5's MPI-IO driver; metadata read and written collectively, so every rank holds
// the same and the file's bytes do not depend on which rank wrote them). Collective.
hid_t create_shared_file(MPI_Comm comm, const std::filesystem::path& path);
// Writes the shared file `path` atomically (dem/files/atomic_file.h): rank 0 names its
// temporary file and reserves `bytes` of the disk for it (a full disk or an unwritable folder
// ends here, before HDF5 writes, in one line naming `path`), every rank fills it with `fill`
// (collective HDF5 calls), and once it is closed rank 0 syncs it and gives it its final name.
// An error on rank 0 or in `fill` on every rank is thrown on every rank. Collective.
void write_shared_file(MPI_Comm comm, const std::filesystem::path& path, std::size_t bytes,
                       const std::function<void(hid_t)>& fill);
// Rows first .. first + count - 1 of a data set of layout.rows rows, each rank of `comm`
// giving its own rows (in order) in one collective H5Dwrite: a hyperslab of the file's rows, or
// none. The data set is allocated when it is made, without fill values (every row is
// written). Throws upgrain::Error on every rank when HDF5 fails on any. Collective.
void write_rows(MPI_Comm comm, hid_t group, const char* name, const void* data, const DatasetLayout& layout,
                hsize_t first, hsize_t count);
template <class T>
void write_rows(MPI_Comm comm, hid_t group, const char* name, const T* data, hsize_t rows, hsize_t cols,
                hsize_t first, hsize_t count) {
  write_rows(comm, group, name, static_cast<const void*>(data),
             DatasetLayout{ElementType<T>::memory(), ElementType<T>::file(), rows, cols}, first, count);
}
// The same for rows in several blocks, each (first, count), in increasing order and apart: the
// data holds the blocks' rows one after the other.
struct RowBlock {
  hsize_t first;
  hsize_t count;
};
void write_row_blocks(MPI_Comm comm, hid_t group, const char* name, const void* data,
                      const DatasetLayout& layout, const std::vector<RowBlock>& blocks);
// A new file for `path` (an AtomicFile's temporary name), built in memory by HDF5's core driver
// without a backing store: the library itself never writes to the disk, so a full disk or a
// write error cannot leave it holding a half-closed file (HDF5 1.10 then crashes when it
// terminates), and every write error is ours to report (flush). `user_block`: bytes reserved
// at the start of the file for the application (checksum_block.h).
hid_t create_file(const std::filesystem::path& path, hsize_t user_block = 0);
// The bytes of a file made by create_file, as they stand.
std::vector<unsigned char> file_image(hid_t file);
// Writes the file's bytes to the path it was made for and syncs them; throws upgrain::Error
// naming `path` (its final name) when that fails (a full disk, a write error). Called before a
// file is committed (atomic_file.h), so a file whose bytes did not all reach the disk never
// gets its final name.
void flush(hid_t file, const std::string& path);

}  // namespace upgrain::dem::io::hdf5
