#pragma once
// Grid stress output: one HDF5 file per evaluation (full, unsymmetrised tensors at full
// precision for each formula asked for, with RAI, counts and solid fraction per cell), an
// XDMF temporal collection so ParaView shows any component as cell data on the grid, and
// one CSV table (a row per evaluation, cell and formula, appended) that is also the stress
// time series. docs/output.md.
#include <filesystem>
#include <string>
#include <vector>

#include "dem/boundary/container.h"
#include "dem/io/csv_series.h"
#include "dem/stress/grid_stress.h"

namespace upgrain::dem::io {

// Which grid stress a run writes (docs/stress.md). No formulas: none.
struct GridStressOptions {
  std::vector<StressFormula> formulas;
  int cells[3] = {3, 3, 4};
  // The grid's box; when not set: the container's footprint, from the floor to the top of
  // the highest grain at each evaluation (the grid follows the assembly as it settles).
  bool fixed_box = false;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  double interval = 0.0;  // s of simulated time between evaluations; 0 = at each snapshot

  [[nodiscard]] bool enabled() const { return !formulas.empty(); }
};

// The grid of one evaluation: the fixed box, or the container footprint up to the top of
// the highest grain (for the unconstrained collapse, widened to the grains' extent).
RegularGrid stress_grid(const GridStressOptions& options, const ParticleStore& p, const BoxContainer& box);

struct GridStressEntry {
  std::string file;  // relative to the output folder
  double time = 0.0;
  long step = 0;
  RegularGrid grid;
};

class GridStressRecorder {
 public:
  // Creates folder/grid_stress/. `formulas` are written in the given order.
  GridStressRecorder(std::filesystem::path folder, std::vector<StressFormula> formulas);

  void record(const RegularGrid& grid, const GridStress& stress, double time, long step);
  [[nodiscard]] const std::vector<GridStressEntry>& entries() const { return entries_; }
  [[nodiscard]] const std::vector<StressFormula>& formulas() const { return formulas_; }
  [[nodiscard]] long csv_rows() const { return csv_.rows(); }
  // A restart: the files of a checkpoint (its entries, its rows of grid_stress.csv).
  void resume(const std::vector<GridStressEntry>& entries, long csv_rows);

 private:
  void flush() const;

  std::filesystem::path folder_;
  std::vector<StressFormula> formulas_;
  std::vector<GridStressEntry> entries_;
  CsvSeries csv_;
};

// Layout of each file (cells in the order (k ny + j) nx + i, x fastest):
//   attributes time, step, sign_convention, volume; /grid/{lo, hi, n, cell_volume};
//   /cells/{particles, internal_contacts, external_contacts, wall_contacts, solid_fraction};
//   /stress/<formula>/{tensor (cells x 9, row-major sigma_ij), rai, sigma_zz}.
void write_grid_stress(const std::filesystem::path& path, const RegularGrid& grid, const GridStress& stress,
                       const std::vector<StressFormula>& formulas, double time, long step);

// "modified nicot" -> "modified_nicot": the name used for groups, columns and fields.
std::string field_name(StressFormula f);

}  // namespace upgrain::dem::io
