#pragma once
// The checks of validate_scene that compare a scene with what can hold it (docs/input.md,
// "Bad input"): this machine's memory, the container (the fill and the stress box), the time
// step (output intervals) and the output folder's name. Each throws upgrain::Error "<where>
// <entry> ..." naming the entries and figures, or adds a one-line warning to in.warnings.
#include <string>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

// Before the fill is planned: a scene that cannot fit is refused before anything is
// allocated.
void check_memory(const SceneInput& in, const std::string& where);
// A gradation whose radii span so many decades that drawing the grains would take hours.
void check_gradation_sampling(const SceneInput& in, const std::string& where);
// The folder exists and is empty (or may be written over), or can be created; no other run holds
// it; a restart's folder has its manifest. Not part of validate_scene: the driver calls it for a
// run, after the command line has chosen the folder (`--output`, `--restart`), and `--check`
// reports it as a note.
void check_output_folder(const SceneInput& in, const std::string& where);
void check_output_intervals(const SceneInput& in, const std::string& where);
// `fill_top`: the height of the highest grain of the fill (dem::plan_fill).
void check_fill_height(SceneInput& in, double fill_top, const std::string& where);
// Grains whose weight alone overlaps them by more than DEM's static bound: a warning, and a
// refusal beyond the runaway-overlap guard's limit (dem/scene/weight_overlap.h).
void check_stiffness(SceneInput& in, const std::string& where);
void check_stress_box(const SceneInput& in, double fill_top, const std::string& where);

}  // namespace upgrain::coupling
