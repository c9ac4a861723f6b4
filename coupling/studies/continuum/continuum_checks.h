#pragma once
// The DEM-vs-continuum study's own checks (docs/study.md), plain C++ for the input layer.
#include <string>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// When the scene's run compares with the continuum: where the continua's material comes from
// (Continuum/material from), the comparison's formulas against those written, the calibration's
// entries when the study calibrates its continua, and what the run keeps for the coarse-grained
// fields with their checks. Throws upgrain::Error prefixed by `where`.
void check_continuum_study(SceneInput& in, const std::string& where);

// What the scene's own study uses of it: the Study, Continuum and CoarseGraining sections when
// Study/compare with continuum is true. The study the driver runs without --study.
inline constexpr StudyUse kContinuumUse{
    .name = "continuum", .scene_study = true, .check = check_continuum_study};

}  // namespace upgrain::coupling
