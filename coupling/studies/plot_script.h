#pragma once
// The plot scripts a run makes its figures with (plot_strain.py, plot_study.py), run by
// Debian's /usr/bin/python3 as a child process out of a stop signal's reach (docs/restart.md,
// "A signal during the end of a run"). A Ctrl-C reaches the whole foreground process group:
// the child died half-way and the report said there were no plots; and std::system ignores
// SIGINT in the caller while it waits, so the driver never saw the signal. Here the child
// starts with SIGINT, SIGTERM and SIGHUP blocked and finishes its plots, and the driver's
// handlers (coupling/run/stop_request.h) see the signal. SIGKILL still ends both.
#include <filesystem>

namespace upgrain::coupling {

// Runs `/usr/bin/python3 script folder` with its output into `log`; true when it exits with 0.
// False, and nothing run, when python or the script is missing.
bool run_plot_script(const std::filesystem::path& script, const std::filesystem::path& folder,
                     const std::filesystem::path& log);

}  // namespace upgrain::coupling
