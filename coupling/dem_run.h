#pragma once
// The DEM part of a driver run: which engine runs it under mpirun (Parallel/DEM engine),
// and the run itself, collective over the communicator.
#include <mpi.h>

#include <functional>
#include <string>

#include "coupling/scene_input.h"

namespace upgrain::coupling {

struct EngineChoice {
  bool mpi = false;    // the MPI engine on every rank; else the serial engine on rank 0
  std::string reason;  // for the log
};

EngineChoice choose_engine(const SceneInput& in, int ranks);

// Collective over `comm`. The result is complete on rank 0 (dem/deposition.h). An error on
// any rank is thrown on every rank.
dem::DepositionResult run_dem(const SceneInput& in, MPI_Comm comm,
                              const std::function<void(const dem::Progress&)>& on_progress);

// Runs `work` on rank 0; an error there becomes the same error on every rank, so no rank
// waits forever in a later message.
void on_rank0(MPI_Comm comm, const std::function<void()>& work);

}  // namespace upgrain::coupling
