#pragma once
// The DEM cells of FEM x DEM written for a viewer (docs/femxdem.md, "Output"): after every
// converged load step, each chosen cell's grains as an HDF5 snapshot, written by the rank that
// owns the cell (femxdem/cells/E_P/cell_NNNN.h5, NNNN the load step; RveCell::write_snapshot),
// and per cell an XDMF series over its snapshots (cell.xdmf, ParaView's Xdmf3 reader), which
// rank 0 writes once every rank has reported its files.
#include <mpi.h>

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "coupling/studies/femxdem/cell_choice.h"
#include "dem/io/hdf5_snapshot.h"
#include "fem/quasi_static/quasi_static_problem.h"

namespace upgrain::coupling {

class CellSnapshots {
 public:
  // `folder`: the study's (femxdem/); `grains`: every cell's grain count.
  CellSnapshots(CellSnapshotChoice choice, std::filesystem::path folder, long grains, MPI_Comm comm);

  // Collective, after a converged load step: the chosen cells among this rank's points.
  void write(const fem::LoadStepRecord& step,
             const std::vector<std::pair<fem::PointPlace, const fem::PointState*>>& owned);
  // A restart's converged steps: their snapshots are on disk, and each cell's series lists them.
  void resumed(const std::vector<fem::LoadStepRecord>& steps);

 private:
  CellSnapshotChoice choice_;
  std::filesystem::path folder_;
  long grains_;
  MPI_Comm comm_;
  std::vector<long> earlier_;                                         // steps before a restart
  std::map<std::string, std::vector<dem::io::SnapshotInfo>> series_;  // rank 0's, per cell
};

}  // namespace upgrain::coupling
