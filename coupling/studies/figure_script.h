#pragma once
// The figure scripts beside the driver's sources (plot_study.py, plot_strain.py,
// plot_accuracy.py), run with /usr/bin/python3 on an output folder, out of a stop signal's reach
// (plot_script.h). What a script writes is
// entered in the folder's manifest (docs/output.md, "Manifest"): the figures it is known to make
// before it runs, so that a run killed meanwhile still knows them for its own, and after it every
// file of the folder it made or changed.
#include <filesystem>
#include <string>
#include <vector>

namespace upgrain::coupling {

struct FigureRun {
  bool ran = false;               // python3 and the script were there
  bool succeeded = false;         // and it exited with 0
  std::vector<std::string> made;  // of `figures`, those that exist after it
};

// Runs `script` (a file name in the driver's script folder) on `folder`, its output into
// folder/`log`. `figures`: the files it is known to write into the folder.
FigureRun run_figure_script(const std::string& script, const std::filesystem::path& folder,
                            const std::string& log, const std::vector<std::string>& figures);

}  // namespace upgrain::coupling
