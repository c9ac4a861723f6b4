#pragma once
// Grid fields on a deal.II mesh: a distributed hexahedral mesh with one coarse cell per
// grid cell (optionally refined), each field as cellwise-constant cell data and as its L2
// projection onto continuous Q1, written as VTU pieces with a PVTU record for ParaView.
// deal.II is confined to grid_mesh.cc: this header needs only MPI. docs/upscale.md.
#include <mpi.h>

#include <filesystem>
#include <string>
#include <vector>

#include "upscale/grid_fields.h"

namespace upgrain::upscale {

struct UpscaleOptions {
  unsigned refinements = 0;  // global refinements of the grid-matching mesh
  bool project_q1 = true;    // also compute and write the L2 projections onto Q1
};

struct UpscaleResult {
  std::vector<std::string> written_files;  // the .pvtu, then the .vtu pieces
  // For tests and round trips, gathered on every rank:
  // [field][grid cell], read from the deal.II cell-data vector over all mesh cells inside
  // each grid cell (NaN if those cells disagree).
  std::vector<std::vector<double>> cell_values_read_back;
  // [field][grid cell]: the projected Q1 field's mean over each grid cell (empty without
  // project_q1).
  std::vector<std::vector<double>> q1_cell_means;
  // [field]: integrals over the box of the projection and of the cellwise field.
  std::vector<double> q1_integral, cellwise_integral;
  // Largest number of CG iterations over the projections.
  unsigned max_cg_iterations = 0;
};

// Collective over `comm`; every rank passes the same fields. Writes
// <folder>/<basename>.pvtu and <folder>/<basename>.<rank>.vtu (folder created if needed);
// the files appear only complete (written into a fresh hidden folder, then renamed). Throws
// upgrain::Error on every rank if anything fails.
UpscaleResult upscale_to_mesh(const GridFields& fields, MPI_Comm comm, const std::filesystem::path& folder,
                              const std::string& basename, const UpscaleOptions& options = {});

}  // namespace upgrain::upscale
