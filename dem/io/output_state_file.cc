#include "dem/io/output_state_file.h"

#include "dem/io/hdf5_util.h"

namespace upgrain::dem::io {

namespace {

// A list of files: their names and a table of `cols` numbers per file.
void write_list(hid_t parent, const std::string& group, const std::vector<std::string>& files,
                const std::vector<double>& values, hsize_t cols) {
  hdf5::Handle g(hdf5::create_group(parent, group), H5Gclose, "create group " + group);
  hdf5::write_attribute(g, "files", files);
  hdf5::write_dataset(g, "values", values.data(), files.size(), cols);
}

std::vector<double> read_list(const hdf5::Reader& in, const std::string& group, hsize_t cols,
                              std::vector<std::string>& files) {
  files = in.text_list_attribute("files", group);
  return in.read<double>(group + "/values", H5T_NATIVE_DOUBLE, files.size(), cols);
}

}  // namespace

void put_grid(const RegularGrid& g, double* nine) {
  for (int d = 0; d < 3; ++d) {
    nine[d] = g.lo[d];
    nine[3 + d] = g.hi[d];
    nine[6 + d] = g.n[d];
  }
}

RegularGrid get_grid(const double* nine, const hdf5::Reader& in) {
  RegularGrid g;
  for (int d = 0; d < 3; ++d) {
    g.lo[d] = nine[d];
    g.hi[d] = nine[3 + d];
    g.n[d] = static_cast<int>(in.whole(nine[6 + d], "a grid's cell count", 0, 1 << 20));
  }
  return g;
}

void write_snapshot_list(hid_t parent, const std::string& group, const std::vector<SnapshotInfo>& list) {
  std::vector<std::string> files;
  std::vector<double> values;
  for (const SnapshotInfo& s : list) {
    files.push_back(s.file);
    values.insert(values.end(),
                  {s.time, static_cast<double>(s.step), static_cast<double>(s.count), s.shapes ? 1.0 : 0.0});
  }
  write_list(parent, group, files, values, 4);
}

std::vector<SnapshotInfo> read_snapshot_list(const hdf5::Reader& in, const std::string& group) {
  std::vector<std::string> files;
  const std::vector<double> v = read_list(in, group, 4, files);
  std::vector<SnapshotInfo> out;
  for (std::size_t k = 0; k < files.size(); ++k)
    out.push_back({files[k], v[4 * k], in.whole(v[4 * k + 1], group + " step"),
                   in.whole(v[4 * k + 2], group + " count", 0), v[4 * k + 3] != 0.0});
  return out;
}

void write_grid_stress_list(hid_t parent, const std::string& group,
                            const std::vector<GridStressEntry>& list) {
  std::vector<std::string> files;
  std::vector<double> values;
  for (const GridStressEntry& e : list) {
    files.push_back(e.file);
    double row[11] = {e.time, static_cast<double>(e.step)};
    put_grid(e.grid, row + 2);
    values.insert(values.end(), row, row + 11);
  }
  write_list(parent, group, files, values, 11);
}

std::vector<GridStressEntry> read_grid_stress_list(const hdf5::Reader& in, const std::string& group) {
  std::vector<std::string> files;
  const std::vector<double> v = read_list(in, group, 11, files);
  std::vector<GridStressEntry> out;
  for (std::size_t k = 0; k < files.size(); ++k)
    out.push_back(
        {files[k], v[11 * k], in.whole(v[11 * k + 1], group + " step"), get_grid(v.data() + 11 * k + 2, in)});
  return out;
}

}  // namespace upgrain::dem::io
