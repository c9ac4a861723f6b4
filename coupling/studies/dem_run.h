#pragma once
// The DEM part of a driver run, collective over the communicator: the engine's options from
// the scene's Parallel section, and the run itself.
#include <mpi.h>

#include <functional>
#include <string>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// The summation, blocks and load balance of the Parallel section.
dem::EngineOptions engine_options(const SceneInput& in);

// Collective over `comm`. The result is complete on rank 0 (coupling/run/scene_run.h). An error on
// any rank is thrown on every rank.
RunResult run_dem(const SceneInput& in, MPI_Comm comm,
                  const std::function<void(const Progress&)>& on_progress);

// Runs `work` on rank 0; an error there becomes the same error on every rank, so no rank
// waits forever in a later message.
void on_rank0(MPI_Comm comm, const std::function<void()>& work);

}  // namespace upgrain::coupling
