#pragma once
// The FEM x DEM study's checkpoints (docs/femxdem.md, "Checkpoints and restart"). After a
// converged load step, when the Checkpoint section's wall interval has passed or the run was
// asked to stop, the solver saves its whole state (fem::QuasiStaticCheckpoints: the mesh and
// partition, the displacement, every DEM cell's engine state) into a working folder; rank 0
// takes those files and the study's tables so far into one checkpoint of the driver's kind
// (<folder>/checkpoints/checkpoint_<step>.h5, a StudyState, coupling/run/checkpoint.h), whole or
// not at all, and the working folder goes. A run asked to stop then stops with RunStopped.
// `upgrain --study femxdem --restart DIR` writes the files back out and the solver resumes from
// them: on the same rank count with the same bits.
#include <mpi.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "coupling/input/scene_input.h"
#include "coupling/run/checkpoint_clock.h"
#include "fem/quasi_static/quasi_static_problem.h"

namespace upgrain::coupling {

class FemxdemCheckpoints {
 public:
  // Collective. On a restart (in.restarting), rank 0 writes the solver's files of the checkpoint
  // it resumes from into a working folder; throws upgrain::CollectiveError naming the checkpoint
  // when they are not there.
  FemxdemCheckpoints(const SceneInput& in, MPI_Comm comm);
  ~FemxdemCheckpoints();
  FemxdemCheckpoints(const FemxdemCheckpoints&) = delete;
  FemxdemCheckpoints& operator=(const FemxdemCheckpoints&) = delete;

  // For the solver. `tables` gives the study's own record of the run so far (rank 0's: kept with
  // each checkpoint); on a restart, `restored` receives the steps the checkpoint had converged and
  // that record back, on every rank (the record on rank 0 only), before the first new step.
  fem::QuasiStaticCheckpoints for_solver(
      std::function<std::string()> tables,
      std::function<void(const std::vector<fem::LoadStepRecord>&, const std::string&)> restored);

  // The load step a restart resumed after; -1 for a fresh run.
  [[nodiscard]] long resumed_after() const { return resumed_after_; }

 private:
  const SceneInput& in_;
  MPI_Comm comm_;
  int rank_ = 0;
  std::filesystem::path work_;   // where the solver saves (and a restart's files are written back)
  std::string resume_stem_;      // empty for a fresh run
  std::string restored_tables_;  // rank 0's, from the checkpoint resumed
  long resumed_after_ = -1;
  CheckpointClock clock_;  // the wall interval, from the last checkpoint's end (or the start)
  std::chrono::steady_clock::time_point saving_since_;  // the one being written: its start
  int stop_ = 0;  // the signal that asked the run to stop, once the ranks agree on it
};

}  // namespace upgrain::coupling
