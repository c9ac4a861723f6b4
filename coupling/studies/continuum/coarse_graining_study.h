#pragma once
// The coarse-grained fields of the DEM's final state on the study's mesh, beside the
// continuum (docs/coarse-graining.md, docs/study.md): the state of rank 0 cut to each rank's
// part of the mesh, the fields at its support or quadrature points, the momentum balance's
// residual, the L2 comparison with the continuum's stress, and mesh/cg_fields.pvtu.
#include <mpi.h>

#include <filesystem>
#include <string>

#include "coupling/input/scene_input.h"
#include "fem/elastic_column.h"
#include "upscale/point_fields_mesh.h"

namespace upgrain::coupling {

struct CoarseGrainingOutcome {
  bool done = false;
  std::string kernel;
  double width = 0.0, diameter = 0.0, cutoff = 0.0;  // m
  double width_in_diameters = 0.0;
  std::string points;  // "support points" or "quadrature points"
  // Largest |residual| and |d(rho v)/dt| over the points, over the largest |rho g|; the
  // residual by differences when asked (else NaN) and its sampling interval.
  double residual = 0.0, momentum_rate = 0.0, residual_by_differences = 0.0, sampling_interval = 0.0;
  long grains = 0, branches = 0, wall_contacts = 0;
  double seconds = 0.0;  // distribution, evaluation, comparison and output (rank 0's wall time)
  upscale::MeshFieldComparison comparison;
  double bed_top = 0.0;  // m: the levels below bed_top - cutoff count for the spread
  [[nodiscard]] double largest_level_spread() const;
};

// Collective. `r` is complete on rank 0; the outcome is the same on every rank.
CoarseGrainingOutcome coarse_grain_on_mesh(const SceneInput& in, const RunResult& r,
                                           const fem::ColumnProblem& problem, const fem::ColumnSolution& sol,
                                           MPI_Comm comm, const std::filesystem::path& folder);

}  // namespace upgrain::coupling
