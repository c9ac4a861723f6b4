#pragma once
// The DEM grid stress set beside the continua of the same container, cell by cell on the
// same grid (docs/study.md): per-cell tensors, sigma_zz and the lateral ratio against depth
// for a centre and an edge column, relative L2 differences per component, the spread of
// sigma_zz across each level, and the share of the weight the side walls carry. The
// continua are the elastic column on rollers (always first), the frictional FEM variants
// and Janssen's slab solution. Plain C++.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "dem/stress/grid_stress.h"
#include "fem/analytic/confined_column.h"

namespace upgrain::coupling {

using Tensor9 = std::array<double, 9>;  // row-major sigma_ij

// One continuum on the grid. The caller fills key, label, cells and wall_share;
// compare_dem_fem fills the rest.
struct ContinuumResult {
  std::string key;             // prefix of its columns in the tables: fem, fem_elastic_friction, janssen, ...
  std::string label;           // for the report and the plots
  std::vector<Tensor9> cells;  // per grid cell, volume averages of sigma
  double wall_share = 0.0;     // share of the bed's weight the side walls carry
  double mean_lateral_ratio = 0.0;   // mean over cells with grains of (s_xx + s_yy) / (2 s_zz)
  std::vector<double> level_spread;  // per level: (max - min) / |mean| of s_zz over the level
  // Per level: the side walls' mean upward shear on the fill (Pa, wall_shear_profile.h).
  std::vector<double> wall_shear;
};

// ||sigma_dem,ij - sigma_c,ij|| over the cells with grains divided by ||sigma_zz|| of the
// hydrostatic column over the same cells (one denominator for every formula and continuum,
// so the rows can be ranked; cells have equal volumes, so these are L2 norms over the bed).
struct Difference {
  Tensor9 component{};
  double tensor = 0.0;  // the same for the whole tensor (Frobenius norm)
};

struct FormulaComparison {
  dem::StressFormula formula;
  std::vector<Difference> against;  // one per continuum, in the order of DemFemComparison::continua
  double mean_lateral_ratio = 0.0;
  std::vector<double> level_spread;
  std::size_t closest = 0;  // index of the continuum with the smallest Difference::tensor
};

struct DemFemComparison {
  dem::RegularGrid grid;
  std::vector<ContinuumResult> continua;  // [0]: the elastic column on rollers
  std::vector<double> analytic_szz;       // per cell: -rho g (H - z_centre), the hydrostatic column
  double k0 = 0.0;
  double dem_wall_share = 0.0;
  // Per level: the DEM's side walls' mean upward shear on the grains, from the wall contacts of
  // the final state (Pa; empty when they were not recorded).
  std::vector<double> dem_wall_shear;
  std::vector<FormulaComparison> formulas;
  int centre_i = 0, centre_j = 0, edge_i = 0, edge_j = 0;
};

// `continua` must hold the elastic column on rollers first; `column` is its exact solution.
DemFemComparison compare_dem_fem(const dem::RegularGrid& grid, const dem::GridStress& dem,
                                 std::vector<ContinuumResult> continua, const fem::ConfinedColumn& column,
                                 double dem_wall_share, const std::vector<dem::StressFormula>& formulas);

// comparison_cells.csv (one row per cell and formula: DEM, the rollers column and their
// difference, the other continua), profiles.csv (centre and edge columns against height),
// relative_l2.csv (per formula and continuum), stress_summary.csv (per formula and
// continuum: wall share, mean lateral ratio, level spread), wall_shear.csv (per level: the
// DEM's and each continuum's side-wall shear). Written atomically.
void write_comparison_tables(const std::filesystem::path& folder, const DemFemComparison& c,
                             const dem::GridStress& dem);

}  // namespace upgrain::coupling
