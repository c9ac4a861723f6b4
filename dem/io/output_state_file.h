#pragma once
// What a checkpoint keeps of the files a run has written (docs/restart.md): the list of its
// snapshots and of its grid-stress files, each as a group of an HDF5 file, and back. A restart
// rewrites the XDMF companions from them.
//
// Layout: a group with the file names as attribute `files` and a table `values`, one row per
// file: snapshots (time, step, count, shapes); grid-stress files (time, step, lo (3), hi (3),
// n (3)).
#include <hdf5.h>

#include <string>
#include <vector>

#include "dem/io/grid_stress_output.h"
#include "dem/io/hdf5_reader.h"
#include "dem/io/hdf5_snapshot.h"

namespace upgrain::dem::io {

void write_snapshot_list(hid_t parent, const std::string& group, const std::vector<SnapshotInfo>& list);
std::vector<SnapshotInfo> read_snapshot_list(const hdf5::Reader& in, const std::string& group);

void write_grid_stress_list(hid_t parent, const std::string& group, const std::vector<GridStressEntry>& list);
std::vector<GridStressEntry> read_grid_stress_list(const hdf5::Reader& in, const std::string& group);

// A regular grid as 9 numbers (lo, hi, n), and back from the file `in` (whose errors name it).
void put_grid(const RegularGrid& g, double* nine);
RegularGrid get_grid(const double* nine, const hdf5::Reader& in);

}  // namespace upgrain::dem::io
