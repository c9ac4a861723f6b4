#pragma once
// When a run writes a checkpoint (docs/restart.md): every `interval` of simulated time (the same
// steps in every run of the scene), every `wall_interval` of wall-clock time, and when the run is
// asked to stop (SIGINT, SIGTERM, SIGHUP). The wall clock and the stop request are each rank's own:
// the ranks agree on them in one reduction, at the points the caller chooses (the DEM run's
// time-series rows, the FEM x DEM study's converged load steps).
#include <mpi.h>

#include <chrono>

#include "coupling/run/output_options.h"

namespace upgrain::coupling {

class CheckpointClock {
 public:
  // `dt` turns the simulated interval into steps (0: the interval is not used); `output` false:
  // a run that writes nothing writes no checkpoint either.
  CheckpointClock(const CheckpointOptions& o, double dt, bool output);

  struct Decision {
    bool write = false;
    int stop = 0;  // the signal that asked the run to stop
  };
  // At step `s`; with `sync`, the ranks agree on the wall clock and the stop request (collective),
  // otherwise only the simulated interval decides.
  [[nodiscard]] Decision at(long s, bool sync, MPI_Comm comm);
  // A checkpoint was written: the wall interval counts from now.
  void written() { last_ = std::chrono::steady_clock::now(); }

 private:
  CheckpointOptions options_;
  bool output_;
  long every_ = 0;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace upgrain::coupling
