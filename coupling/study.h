#pragma once
// A DEM-vs-continuum study (docs/study.md): DEM deposition (relaxed to static equilibrium)
// -> grid stress -> the continuum column of the same container on a deal.II mesh that
// matches the grid -> comparison tables, the DEM and FEM fields on one mesh (VTU), plots
// and a Markdown report, all in the run's output folder.
#include <mpi.h>

#include <functional>

#include "coupling/scene_input.h"

namespace upgrain::coupling {

// Collective over `comm`. The DEM runs on every rank (coupling/dem_run.h); the continuum
// solve and the mesh output use every rank too. Returns the process exit code.
// on_dem_done is called on rank 0 once the DEM part has finished.
int run_study(const SceneInput& in, MPI_Comm comm, const std::function<void(const Progress&)>& on_progress,
              const std::function<void(const RunResult&)>& on_dem_done);

}  // namespace upgrain::coupling
