#pragma once
// Small RAII and write helpers over the HDF5 C API, shared by the snapshot and grid-stress
// writers. Errors become upgrain::Error naming what could not be done.
#include <hdf5.h>

#include <string>
#include <vector>

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

// A rows x cols data set (1-D when cols == 1).
void write_dataset(hid_t group, const char* name, hid_t mem_type, hid_t file_type, const void* data,
                   hsize_t rows, hsize_t cols);
void write_attribute(hid_t obj, const char* name, double value);
void write_attribute(hid_t obj, const char* name, const std::string& value);
// A 1-D attribute of fixed-length strings (each padded to the longest).
void write_attribute(hid_t obj, const char* name, const std::vector<std::string>& values);
hid_t create_group(hid_t parent, const std::string& name);

}  // namespace upgrain::dem::io::hdf5
