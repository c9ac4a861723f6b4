#pragma once
// Stopping a run cleanly when it is asked to (docs/restart.md): SIGINT, SIGTERM and SIGHUP set
// a flag that the run reads at its next time-series row, on every rank at once; it then writes
// a checkpoint (when it writes output), ends its files and stops with RunStopped. A second
// signal of the same kind ends the process at once, as without the handlers.
#include <mpi.h>

#include <filesystem>
#include <string>

#include "dem/core/error.h"

namespace upgrain::coupling {

// Installs the handlers (the driver calls it once, before the run).
void install_stop_handlers();
// The signal received, 0 if none. Async-signal-safe to set, cheap to read.
int stop_signal();
// For tests: as if `signal` had arrived.
void request_stop(int signal);

// Collective: throws RunStopped (no checkpoint) on every rank when any rank received a signal.
// For loops outside a scene's run (the calibration's tests), which write no checkpoint.
void stop_if_requested(MPI_Comm comm, long step);

// Collective: the signal any rank received so far, 0 if none (the same on every rank). The
// driver asks once its run has written everything (docs/restart.md, "A signal during the end
// of a run").
int stop_signal_received(MPI_Comm comm);

// What a stopped run throws once its checkpoint is written. The driver's exit code for it is
// 128 + the signal (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP), as a shell reports a
// process ended by that signal.
class RunStopped : public Error {
 public:
  // `without_checkpoint`: what to say instead of "no checkpoint (no output)" when there is none
  // (where the run stopped, what it left); `during`: the stage it stopped in, when not the steps.
  RunStopped(int signal, long step, std::filesystem::path checkpoint,
             const std::string& without_checkpoint = {}, const std::string& during = {});
  [[nodiscard]] int signal() const { return signal_; }
  [[nodiscard]] long step() const { return step_; }
  // Empty when the run wrote no output (so no checkpoint).
  [[nodiscard]] const std::filesystem::path& checkpoint() const { return checkpoint_; }

 private:
  int signal_;
  long step_;
  std::filesystem::path checkpoint_;
};

}  // namespace upgrain::coupling
