#pragma once
// The accuracy study's own checks (docs/accuracy.md), plain C++ for the input layer.
#include <string>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// The Accuracy section's knobs and values, once the scene itself is known sound: each setting
// is made (knob_settings) and refused with its entry named, before any run. Throws
// upgrain::Error prefixed by `where`.
void check_accuracy_study(SceneInput& in, const std::string& where);

// What the accuracy study uses of a scene: the Continuum section's material for its continuum
// knob, the scene's lid, and its own checks.
inline constexpr StudyUse kAccuracyUse{
    .name = "accuracy", .continuum_material = true, .check = check_accuracy_study};

}  // namespace upgrain::coupling
