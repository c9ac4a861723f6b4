#pragma once
// Grid strain output, beside the grid stress: one HDF5 file per evaluation under
// grid_strain/ (every tensor at full precision, validity flags and reason codes per cell),
// an XDMF temporal collection grid_strain.xdmf so ParaView shows ln J, the equivalent
// shear strain, the validity and F as cell data on the grid, and one CSV table
// grid_strain.csv (a row per evaluation, cell and definition). docs/strain.md.
#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "dem/core/box.h"
#include "dem/io/csv_series.h"
#include "upscale/strain/grid_strain.h"
#include "upscale/strain/grid_stress_rates.h"

namespace upgrain::upscale {

using dem::Box;
using dem::GlobalId;
using dem::RegularGrid;
using dem::io::CsvSeries;

// Which grid strain a run writes (docs/strain.md). Evaluated with the grid stress, on its
// grid (Stress/grid cells and box), so it needs the grid stress enabled.
struct GridStrainOutputOptions {
  bool enabled = false;
  // t0 (s): the reference state is the initial state when 0, otherwise the first grid-stress
  // evaluation at or after t0. No strain is written before it.
  double reference_time = 0.0;
  GridStrainOptions kernel;  // set (Lagrangian or Eulerian) and definitions
  // The grid-stress formula whose cell series gives the objective stress rates written with
  // the strain (grid_stress_rates.h); it must be among the formulas written.
  dem::StressFormula rate_formula = dem::StressFormula::bagi;
};

struct GridStrainEntry {
  std::string file;  // relative to the output folder
  double time = 0.0;
  long step = 0;
  RegularGrid grid;
  std::array<bool, kStrainDefinitionCount> computed = {false, false};
  bool rates = false;  // the file holds the objective stress rates
};

class GridStrainRecorder {
 public:
  // Creates folder/grid_strain/.
  explicit GridStrainRecorder(std::filesystem::path folder);

  // `rates` (optional): the objective stress rates of the same output, written beside the
  // strain (upscale/strain/grid_stress_rates.h). Without them the CSV's rate columns are zero
  // with reason code no_history.
  void record(const GridStrain& strain, const GridStressRates* rates = nullptr);
  [[nodiscard]] const std::vector<GridStrainEntry>& entries() const { return entries_; }
  [[nodiscard]] long csv_rows() const { return csv_.rows(); }
  // A restart: the files of a checkpoint (its entries, its rows of grid_strain.csv).
  void resume(const std::vector<GridStrainEntry>& entries, long csv_rows);

 private:
  void flush() const;

  std::filesystem::path folder_;
  std::vector<GridStrainEntry> entries_;
  CsvSeries csv_;
};

// Layout of each file (cells in the order (k ny + j) nx + i, x fastest):
//   attributes time, step, reference_time, reference_step, set ("lagrangian" or
//     "eulerian"), untracked, reason_names (string list: the name of each reason code);
//   /grid/{lo, hi, n}: the grid whose cells define the sets; /cells/particles;
//   /<definition>/ for best_fit and tessellation (those computed):
//     cells x 9 (row-major, T_ij at 3 i + j): F, L, F_increment, E, e, hencky (ln V), R, D, W;
//     cells: J, ln_J, equivalent_shear_strain, equivalent_shear_rate, increment_ln_J,
//     increment_equivalent_shear_strain, residual_rms;
//     int32 per cell: F_valid, F_reason, L_valid, L_reason, increment_valid, increment_reason;
//     with rates: cells x 9 stress_rate (sigma_dot), jaumann_rate, green_naghdi_rate,
//     truesdell_rate, oldroyd_rate; int32 rate_valid, rate_reason, green_naghdi_valid,
//     green_naghdi_reason;
//   with rates, /rates/stress (cells x 9, the cell stress differenced) and attributes
//     formula, outputs_used, order, difference (how sigma_dot was taken).
void write_grid_strain(const std::filesystem::path& path, const GridStrain& strain,
                       const GridStressRates* rates = nullptr);

// Strain per compute grid of an MPI run (docs/strain.md, "Compute grids"): one HDF5 file per
// evaluation under compute_grid_strain/ and the table compute_grid_strain.csv (a row per
// evaluation, block and definition). The blocks depend on the rank count and move with the load
// balance, so, unlike the fixed grid's, these files are not rank-independent.
class ComputeGridStrainRecorder {
 public:
  // Creates folder/compute_grid_strain/.
  explicit ComputeGridStrainRecorder(std::filesystem::path folder);
  // `blocks`: the boxes of the blocks whose particles make the sets (Lagrangian: at t0,
  // Eulerian: now); `id`, `member`: the block of each particle of a set, ascending ids.
  void record(const GridStrain& strain, const std::vector<Box>& blocks, std::span<const GlobalId> id,
              std::span<const int> member);
  [[nodiscard]] long csv_rows() const { return csv_.rows(); }
  void resume(long csv_rows) { csv_.resume(csv_rows); }

 private:
  std::filesystem::path folder_;
  CsvSeries csv_;
};

// Layout: the attributes of write_grid_strain; /blocks/{lo, hi} (blocks x 3), /blocks/particles;
// /sets/id, /sets/block (the block of each particle of a set); the definition groups of
// write_grid_strain, one entry per block, without rates.
void write_compute_grid_strain(const std::filesystem::path& path, const GridStrain& strain,
                               const std::vector<Box>& blocks, std::span<const GlobalId> id,
                               std::span<const int> member);

// "best fit" -> "best_fit": the name used for groups, columns and fields.
std::string field_name(StrainDefinition d);

}  // namespace upgrain::upscale
