#pragma once
// The FEM x DEM study's own checks (docs/femxdem.md), plain C++ for the input layer.
#include <string>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// `upgrain --study femxdem`: the FEMxDEM section's entries against each other. Throws
// upgrain::Error prefixed by `where`.
void check_femxdem_study(SceneInput& in, const std::string& where);

// What the study uses of a scene: its grains and contact law (the DEM cells' material) and the
// FEMxDEM section; not its container, fill or lid.
inline constexpr StudyUse kFemxdemUse{.name = "femxdem",
                                      .scene_lid = false,
                                      .own_state = true,
                                      .runs_scene = false,
                                      .check = check_femxdem_study};

}  // namespace upgrain::coupling
