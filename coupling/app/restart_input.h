#pragma once
// The scene of a run to continue (upgrain --restart DIR [scene.prm]; docs/restart.md).
#include <string>
#include <vector>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// The scene of a run to continue (upgrain --restart DIR [scene.prm]): rank 0 reads the newest
// valid checkpoint of DIR, every rank the scene it stores; a scene file given as well may change
// only what a restart may (coupling::differing_parameters), and may not end before the
// checkpoint (coupling/run/resume_point.h). `notes` receives what the log should say (refused
// checkpoints, where the run resumes), on rank 0.
// Collective over MPI_COMM_WORLD; a refusal is every rank's.
SceneInput restart_input(const std::string& dir, const std::string& file, const StudyUse& use,
                         std::vector<std::string>& notes);

}  // namespace upgrain::coupling
