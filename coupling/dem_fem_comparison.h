#pragma once
// The DEM grid stress set beside the continuum solution of the same container, cell by
// cell on the same grid (docs/study.md): per-cell tensors and differences, sigma_zz and
// the lateral ratio against depth for a centre and an edge column, relative L2
// differences per component, and the spread of sigma_zz across each level. Plain C++.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "dem/stress/grid_stress.h"
#include "fem/analytic/confined_column.h"

namespace upgrain::coupling {

using Tensor9 = std::array<double, 9>;  // row-major sigma_ij

struct FormulaComparison {
  dem::StressFormula formula;
  // ||sigma_dem,ij - sigma_fem,ij|| over the cells with grains, divided by ||sigma_fem,zz||
  // over the same cells (cells have equal volumes, so these are L2 norms over the bed).
  Tensor9 relative_l2{};
  double mean_lateral_ratio = 0.0;   // mean over cells with grains of (s_xx + s_yy) / (2 s_zz)
  std::vector<double> level_spread;  // per level: (max - min) / |mean| of s_zz over the level
};

struct DemFemComparison {
  dem::RegularGrid grid;
  std::vector<Tensor9> fem;          // per cell, volume averages of the continuum stress
  std::vector<double> analytic_szz;  // per cell: -rho g (H - z_centre)
  double k0 = 0.0;
  std::vector<FormulaComparison> formulas;
  std::vector<double> fem_level_spread;
  double fem_mean_lateral_ratio = 0.0;
  int centre_i = 0, centre_j = 0, edge_i = 0, edge_j = 0;
};

DemFemComparison compare_dem_fem(const dem::RegularGrid& grid, const dem::GridStress& dem,
                                 const std::vector<Tensor9>& fem, const fem::ConfinedColumn& column,
                                 const std::vector<dem::StressFormula>& formulas);

// comparison_cells.csv (one row per cell and formula: DEM, FEM, difference), profiles.csv
// (centre and edge columns against depth), relative_l2.csv. Written atomically.
void write_comparison_tables(const std::filesystem::path& folder, const DemFemComparison& c,
                             const dem::GridStress& dem);

}  // namespace upgrain::coupling
