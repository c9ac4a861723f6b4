#include "coupling/studies/femxdem/cell_snapshots.h"

#include <cstdio>

#include "coupling/femxdem/rve_point.h"
#include "dem/core/error.h"
#include "dem/files/output_journal.h"
#include "dem/parallel/exchange.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

namespace {

std::string cell_name(const fem::PointPlace& p) {
  return std::to_string(element_of(p.cell)) + "_" + std::to_string(p.index);
}

std::string snapshot_name(long step) {
  char name[32];
  std::snprintf(name, sizeof name, "cell_%04ld.h5", step);
  return name;
}

dem::io::SnapshotInfo info(long step, long grains) {
  // The load step as ParaView's time.
  return {snapshot_name(step), static_cast<double>(step), step, grains, false};
}

}  // namespace

CellSnapshots::CellSnapshots(CellSnapshotChoice choice, fs::path folder, long grains, MPI_Comm comm)
    : choice_(std::move(choice)), folder_(std::move(folder)), grains_(grains), comm_(comm) {}

void CellSnapshots::resumed(const std::vector<fem::LoadStepRecord>& steps) {
  for (const fem::LoadStepRecord& s : steps) earlier_.push_back(static_cast<long>(s.step));
}

void CellSnapshots::write(const fem::LoadStepRecord& step,
                          const std::vector<std::pair<fem::PointPlace, const fem::PointState*>>& owned) {
  if (choice_.empty()) return;
  std::string mine, error;
  try {
    for (const auto& [place, state] : owned) {
      const auto* cell = dynamic_cast<const RveCell*>(state);
      if (cell == nullptr || !choice_.chooses(place)) continue;
      const std::string name = cell_name(place);
      fs::create_directories(folder_ / "cells" / name);
      cell->write_snapshot(folder_ / "cells" / name / snapshot_name(step.step),
                           static_cast<double>(step.step), static_cast<long>(step.step));
      mine += name + "\n";
    }
  } catch (const std::exception& e) {
    error = e.what();
  }
  dem::throw_if_any(comm_, error);
  // Every rank's cells to rank 0, which enters the files in the run's journal and writes the series.
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &ranks);
  int length = static_cast<int>(mine.size());
  std::vector<int> lengths(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks), 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, comm_);
  int total = 0;
  for (int r = 0; r < ranks; ++r) {
    offsets[static_cast<std::size_t>(r)] = total;
    total += lengths[static_cast<std::size_t>(r)];
  }
  std::string all(rank == 0 ? static_cast<std::size_t>(total) : 0, '\0');
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, comm_);
  dem::run_on_root(comm_, [&] {
    std::size_t from = 0;
    while (from < all.size()) {
      const std::size_t end = all.find('\n', from);
      const std::string name = all.substr(from, end - from);
      from = end + 1;
      const fs::path dir = folder_ / "cells" / name;
      dem::io::note_written(dir / snapshot_name(step.step));
      auto [series, first] = series_.try_emplace(name);
      if (first)
        for (const long s : earlier_) series->second.push_back(info(s, grains_));
      series->second.push_back(info(static_cast<long>(step.step), grains_));
      dem::io::write_xdmf(dir / "cell.xdmf", series->second);
    }
  });
}

}  // namespace upgrain::coupling
