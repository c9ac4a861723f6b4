#pragma once
// A deal.II DataOut written as one .vtu piece per rank and a .pvtu record, atomically and
// entered in the output folder's journal (docs/output.md, "Manifest"). Private to upgrain::fem:
// it includes deal.II, so only the solvers' translation units include it.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_out.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dem/files/atomic_file.h"
#include "dem/files/output_journal.h"
#include "dem/files/undated_vtk.h"

namespace upgrain::fem {

// One .vtu piece per rank and a .pvtu record, each written under a temporary name and
// renamed (dem/files/atomic_file.h). The record is written last, after every rank reported
// its piece complete, so a reader never finds a record that points at a missing piece.
// Every rank reports failure through an all-reduce instead of throwing alone, which would
// leave the other ranks waiting in the next collective call. `data_out` has its patches
// built; the files are `name`.pvtu and `name`.procRRRR.vtu.
template <int dim>
void write_pieces_and_record(const dealii::DataOut<dim>& data_out, const std::string& folder,
                             const std::string& name, MPI_Comm comm) {
  const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const auto piece_name = [&name](unsigned int r) {
    return name + ".proc" + dealii::Utilities::int_to_string(r, 4) + ".vtu";
  };
  const auto all_succeeded = [comm](const std::string& local_error) {
    return dealii::Utilities::MPI::min(local_error.empty() ? 1 : 0, comm) == 1;
  };
  const std::filesystem::path dir(folder);
  std::vector<std::filesystem::path> piece_paths;
  for (unsigned int r = 0; r < n_ranks; ++r) piece_paths.push_back(dir / piece_name(r));
  dem::io::note_pieces_writing(comm, dir, piece_paths);  // docs/output.md, "Manifest"
  std::string error;
  try {
    if (!std::filesystem::is_directory(dir)) throw std::runtime_error("cannot create folder " + folder);
    std::ostringstream vtu;
    data_out.write_vtu(vtu);
    dem::io::write_text_atomically(dir / piece_name(rank), dem::io::undated_vtk(vtu.str()));
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!all_succeeded(error))
    throw std::runtime_error("fem output: " +
                             (error.empty() ? "another rank failed to write its piece" : error));

  if (rank == 0) {
    try {
      std::vector<std::string> pieces;
      for (unsigned int r = 0; r < n_ranks; ++r) pieces.push_back(piece_name(r));
      std::ostringstream pvtu;
      data_out.write_pvtu_record(pvtu, pieces);
      dem::io::write_text_atomically(dir / (name + ".pvtu"), dem::io::undated_vtk(pvtu.str()));
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!all_succeeded(error))
    throw std::runtime_error("fem output: " +
                             (error.empty() ? "rank 0 failed to write " + name + ".pvtu" : error));
  dem::io::note_pieces_written(comm, piece_paths);
}

}  // namespace upgrain::fem
