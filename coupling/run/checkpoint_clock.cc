#include "coupling/run/checkpoint_clock.h"

#include <algorithm>
#include <cmath>

#include "coupling/run/stop_request.h"

namespace upgrain::coupling {

CheckpointClock::CheckpointClock(const CheckpointOptions& o, double dt, bool output)
    : options_(o), output_(output), last_(std::chrono::steady_clock::now()) {
  if (output && o.interval > 0.0 && dt > 0.0)
    every_ = std::max(1L, static_cast<long>(std::llround(o.interval / dt)));
}

CheckpointClock::Decision CheckpointClock::at(long s, bool sync, MPI_Comm comm) {
  Decision d;
  d.write = every_ > 0 && s % every_ == 0;
  if (!sync) return d;
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count();
  int local[2] = {stop_signal(), output_ && options_.wall_interval > 0.0 && since >= options_.wall_interval};
  int global[2] = {0, 0};
  MPI_Allreduce(local, global, 2, MPI_INT, MPI_MAX, comm);
  d.stop = global[0];
  d.write = d.write || (output_ && (global[0] != 0 || global[1] != 0));
  return d;
}

}  // namespace upgrain::coupling
