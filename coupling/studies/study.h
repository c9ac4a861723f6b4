#pragma once
// A study the driver runs on a scene (docs/architecture.md, "How to add a study"): its row in the
// table (study_table.h) names it, says which sections it uses, and runs it.
#include <mpi.h>

#include <functional>
#include <string_view>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// What the driver shows while a study runs (called on rank 0).
struct StudyHooks {
  std::function<void(const Progress&)> progress;   // the DEM run's progress line
  std::function<void(const RunResult&)> dem_done;  // the scene's own DEM run has finished
};

struct Study {
  // Its name as `upgrain --study` takes it, the sections it uses and its own checks: plain C++
  // that the input layer runs (coupling/input/study_use.h).
  StudyUse use;
  // What `upgrain --help` says of it, after "--study <name>": lines of at most 62 characters.
  std::string_view help;
  // Collective over `comm`: the study of the validated scene `in`, into its Output/folder.
  // Returns the process exit code.
  int (*run)(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks);
};

}  // namespace upgrain::coupling
