#pragma once
// XDMF 3 temporal collections of cell data on a regular grid (grid stress, grid strain):
// one 3DCoRectMesh per evaluation, with dimensions, origin and spacing in z, y, x order and
// cell-centred attributes read from the evaluation's HDF5 file, for ParaView's Xdmf3 reader.
#include <filesystem>
#include <string>
#include <vector>

#include "dem/stress/grid_stress.h"

namespace upgrain::dem::io {

struct CellAttribute {
  std::string name;
  std::string kind;  // "Scalar", "Tensor", ...
  std::string path;  // data set in the HDF5 file
  int components = 1;
  std::string number_type = "Float";
  int precision = 8;
};

struct GridXdmfStep {
  std::string file;  // HDF5 file, relative to the XDMF file's folder
  double time = 0.0;
  long step = 0;
  RegularGrid grid;
  std::vector<CellAttribute> attributes;
};

// Writes the collection atomically.
void write_grid_xdmf(const std::filesystem::path& path, const std::string& collection,
                     const std::vector<GridXdmfStep>& steps);

}  // namespace upgrain::dem::io
