#pragma once
// What a run leaves in its output folder: HDF5 snapshots with an XDMF companion, a CSV
// time series of energies and contacts, a CSV series of the walls' motion and loads, and a JSON
// summary. Every file is written
// atomically; the time series is appended to at each snapshot (csv_series.h).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "dem/core/plane_wall.h"
#include "dem/engine/diagnostics.h"
#include "dem/engine/energy.h"
#include "dem/io/csv_series.h"
#include "dem/io/hdf5_snapshot.h"

namespace upgrain::dem::io {

class RunRecorder {
 public:
  // Creates the folder (and its snapshots/ subfolder).
  explicit RunRecorder(std::filesystem::path folder);

  // One row of the time series, and a snapshot of a whole state sorted by id.
  void record_series(double time, long step, const EnergyBalance& e, double balance_error,
                     const StepDiagnostics& d);
  void write_snapshot(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                      const std::vector<Vec3>& wall_forces, double time, long step, bool images = false);
  // A snapshot's name relative to the folder (snapshots/particles_<step>.h5): what every rank
  // writes into collectively (write_snapshot(MPI_Comm, ...)) before rank 0 lists it here.
  [[nodiscard]] static std::filesystem::path snapshot_name(long step);
  // Lists a snapshot written (particles.xdmf rewritten, the series appended).
  void add_snapshot(const SnapshotInfo& s);
  // One row of walls.csv per wall in the scene (not removed), at a time-series row: where the
  // wall is and how fast it moves, and the force the particles exert on it (wall_forces). The
  // displacement is from the wall's point at its first row.
  void record_walls(double time, long step, const std::vector<PlaneWall>& walls,
                    const std::vector<bool>& present, const std::vector<Vec3>& wall_forces);
  // Appends the new rows to time_series.csv and walls.csv and rewrites particles.xdmf.
  void flush();
  void write_summary(const std::map<std::string, std::string>& entries) const;

  [[nodiscard]] const std::filesystem::path& folder() const { return folder_; }

  // What a checkpoint keeps (after a flush): the rows of time_series.csv and walls.csv, the
  // walls' points at their first rows (by wall index) and the snapshots.
  struct State {
    long series_rows = 0;
    long wall_rows = 0;
    std::vector<Vec3> wall_origins;
    std::vector<SnapshotInfo> snapshots;
  };
  [[nodiscard]] State state() const { return {series_.rows(), walls_.rows(), wall_origins_, snapshots_}; }
  // A restart: the series cut back to the checkpoint's rows and particles.xdmf rewritten with
  // its snapshots.
  void resume(const State& s);
  [[nodiscard]] const std::vector<std::string>& series_rows() const { return rows_; }

 private:
  std::filesystem::path folder_;
  std::vector<std::string> rows_;
  std::size_t rows_written_ = 0;
  CsvSeries series_;
  std::vector<std::string> wall_rows_;
  std::size_t wall_rows_written_ = 0;
  CsvSeries walls_;
  std::vector<Vec3> wall_origins_;
  std::vector<SnapshotInfo> snapshots_;
};

}  // namespace upgrain::dem::io
