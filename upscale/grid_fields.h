#pragma once
// The per-cell fields of one DEM grid evaluation as plain numbers: the input of the
// upscaling to a deal.II mesh (upscale/grid_mesh.h), filled either from a result in memory
// or from a file written by dem::io::write_grid_stress. No deal.II here, so the DEM side
// and its tests need none. docs/upscale.md.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "dem/stress/grid_stress.h"
#include "dem/stress/stress_formula.h"

namespace upgrain::dem::io::hdf5 {
class Reader;
}

namespace upgrain::upscale {

struct GridFields {
  std::array<int, 3> n{1, 1, 1};  // cells along x, y, z
  std::array<double, 3> lo{}, hi{};
  std::vector<std::string> names;  // one per scalar field, e.g. "bagi_s_zz", "particles"
  // [field][cell], cell = (k ny + j) nx + i (x fastest), as dem::RegularGrid.
  std::vector<std::vector<double>> values;
  double time = 0.0;
  long step = 0;

  // Appends a field. Throws upgrain::Error naming the field when its size is not
  // num_cells() or the name is already taken.
  void add(std::string name, std::vector<double> v);
  // The field called `name`; throws upgrain::Error naming it and listing the fields there are.
  [[nodiscard]] const std::vector<double>& operator[](const std::string& name) const;
  [[nodiscard]] int num_cells() const { return n[0] * n[1] * n[2]; }
};

// From memory. For each formula asked for (in the given order): the nine components
// "<formula>_s_xx", "<formula>_s_xy", ..., "<formula>_s_zz" (row-major sigma_ij, formula
// names as dem::io::field_name, e.g. "modified_nicot_s_zz"), then "<formula>_rai"; then
// "particles", "internal_contacts", "external_contacts", "wall_contacts", "solid_fraction".
GridFields grid_fields_from_stress(const dem::RegularGrid& grid, const dem::GridStress& stress,
                                   const std::vector<dem::StressFormula>& formulas);

// From a file written by dem::io::write_grid_stress: the same field names, for every
// formula present in /stress (the seven known ones in the order of dem::StressFormula, any
// other group after them by name). Errors name the file and the missing dataset.
GridFields read_grid_fields(const std::filesystem::path& h5_file);

// The grid and the time of a grid file, as the grid-stress and grid-strain files both hold
// them (/grid/n, /grid/lo, /grid/hi; the attributes time and step), without fields. Errors
// name the file (`in`'s kind and path) and what is missing or not a cell count.
GridFields read_grid_header(const dem::io::hdf5::Reader& in);

}  // namespace upgrain::upscale
