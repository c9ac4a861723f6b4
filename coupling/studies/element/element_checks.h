#pragma once
// The element tests' own checks (docs/element-tests.md), plain C++ for the input layer.
#include <string>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// `upgrain --study element`: a fully periodic cell without a pour, the Element test section's
// entries against each other and the time step. Throws upgrain::Error prefixed by `where`.
void check_element_study(SceneInput& in, const std::string& where);

// What the element study uses of a scene: its grains, its cell and the Element test section;
// no lid (it has no walls).
inline constexpr StudyUse kElementUse{
    .name = "element", .scene_lid = false, .checkpoints = false, .check = check_element_study};

}  // namespace upgrain::coupling
