#pragma once
// The DEM-vs-continuum study (docs/study.md): DEM deposition (relaxed to static equilibrium)
// -> grid stress -> the continuum column of the same container on a deal.II mesh that
// matches the grid -> comparison tables, the DEM and FEM fields on one mesh (VTU), plots
// and a Markdown report, all in the run's output folder.
#include <mpi.h>

#include "coupling/studies/study.h"

namespace upgrain::coupling {

// The scene's own study, run without --study: its DEM run, and the DEM-vs-continuum chain unless
// Study/compare with continuum is false. Collective over `comm`. The DEM runs on every rank
// (coupling/studies/dem_run.h); the continuum solve and the mesh output use every rank too. Returns
// the process exit code. hooks.dem_done is called on rank 0 once the DEM part has finished.
int run_continuum_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks);

}  // namespace upgrain::coupling
