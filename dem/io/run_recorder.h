#pragma once
// What a run leaves in its output folder: HDF5 snapshots with an XDMF companion, a CSV
// time series of energies and contacts, and a JSON summary. Every file is written
// atomically; the time series is rewritten whole at each snapshot.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "dem/io/hdf5_snapshot.h"
#include "dem/simulation.h"

namespace upgrain::dem::io {

struct OutputOptions {
  std::filesystem::path folder = "upgrain-output";
  double snapshot_interval = 0.05;  // s of simulated time; 0 = only first and last
  double series_interval = 0.005;   // s of simulated time between time-series rows
};

class RunRecorder {
 public:
  // Creates the folder (and its snapshots/ subfolder).
  explicit RunRecorder(OutputOptions options);

  void record_series(const Simulation& sim);
  void write_snapshot(const Simulation& sim);
  // Rewrites time_series.csv and particles.xdmf.
  void flush() const;
  void write_summary(const std::map<std::string, std::string>& entries) const;

  [[nodiscard]] const OutputOptions& options() const { return options_; }
  [[nodiscard]] const std::vector<std::string>& series_rows() const { return rows_; }

 private:
  OutputOptions options_;
  std::vector<std::string> rows_;
  std::vector<SnapshotInfo> snapshots_;
};

}  // namespace upgrain::dem::io
