#include "coupling/run/stop_request.h"

#include <signal.h>

#include <csignal>
#include <cstring>

namespace upgrain::coupling {

namespace {
volatile std::sig_atomic_t g_signal = 0;
extern "C" void on_stop_signal(int s) { g_signal = s; }
}  // namespace

void install_stop_handlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // a second signal: the default action
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaction(s, &action, nullptr);
}

int stop_signal() { return g_signal; }

void request_stop(int signal) { g_signal = signal; }

int stop_signal_received(MPI_Comm comm) {
  int signal = stop_signal();
  MPI_Allreduce(MPI_IN_PLACE, &signal, 1, MPI_INT, MPI_MAX, comm);
  return signal;
}

void stop_if_requested(MPI_Comm comm, long step) {
  if (const int signal = stop_signal_received(comm); signal != 0) throw RunStopped(signal, step, {});
}

RunStopped::RunStopped(int signal, long step, std::filesystem::path checkpoint,
                       const std::string& without_checkpoint, const std::string& during)
    : Error("stopped by signal " + std::to_string(signal) + " (" + strsignal(signal) + ") " +
            (during.empty() ? std::string() : during + " ") + "after step " + std::to_string(step) +
            (!checkpoint.empty()          ? ", checkpoint " + checkpoint.string()
             : without_checkpoint.empty() ? std::string(", no checkpoint (no output)")
                                          : ", " + without_checkpoint)),
      signal_(signal),
      step_(step),
      checkpoint_(std::move(checkpoint)) {}

}  // namespace upgrain::coupling
