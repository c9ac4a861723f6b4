#pragma once
// The calibration's own checks (docs/calibration.md), plain C++ for the input layer: whether its
// tests can load a scene's bed, and the Calibration section's entries against each other.
#include <string>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// Why the calibration's tests cannot load this scene's bed: a contact law without the servo's
// stiffness bound, or a box with a gate or opening walls. Empty when they can. (`--study
// calibration` deposits without the scene's lid; a study keeps it on its bed, so its own
// calibration is refused there too: Continuum/material from.)
std::string calibration_refusal(const SceneInput& in);

// The Calibration section's entries against each other and the time step, wherever the
// calibration runs (calibrates()). Throws upgrain::Error prefixed by `where`.
void check_calibration(const SceneInput& in, const std::string& where);

// `upgrain --study calibration`: the bed can be loaded, then check_calibration.
void check_calibration_study(SceneInput& in, const std::string& where);

// What the calibration study uses of a scene: the Calibration section, always; it deposits the
// bed without the scene's lid and places its own.
inline constexpr StudyUse kCalibrationUse{
    .name = "calibration", .scene_lid = false, .calibrates = true, .check = check_calibration_study};

}  // namespace upgrain::coupling
