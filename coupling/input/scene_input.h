#pragma once
// What the driver hands to the DEM engine after reading and validating a scene file.
#include <array>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "coupling/input/study_use.h"
#include "coupling/run/output_options.h"
#include "coupling/run/scene_run.h"
#include "coupling/studies/accuracy/accuracy_options.h"
#include "coupling/studies/calibration/calibration_options.h"
#include "coupling/studies/continuum/study_options.h"
#include "coupling/studies/element/element_options.h"
#include "coupling/studies/femxdem/femxdem_options.h"
#include "dem/scene/effect_choice.h"
#include "dem/scene/scene_config.h"

namespace upgrain::coupling {

// The Parallel section: the summation, the blocks and the load balance of the DEM engine.
struct ParallelInput {
  dem::Summation summation = dem::Summation::deterministic;
  // Parallel/DEM engine of older scene files (auto, serial or mpi): no longer used, since one
  // engine runs every rank count; the driver says so when it is not auto.
  std::string legacy_engine = "auto";
  std::array<int, 3> blocks{0, 0, 0};  // all 0: chosen from the rank count and the box
  double balance_interval = 0.01;      // s of simulated time; 0 = fixed blocks
  bool balance_by_pairs = false;       // cost: pair slots instead of particles
};

struct SceneInput {
  std::string source;  // file name, or "built-in default scene"
  // The study the command line runs on the scene (upgrain --study; docs/input.md, "Checks across
  // parameters"): a section's checks run only when the study uses the section.
  StudyUse use;
  // The folder of the scene file, where a relative Particles/initial packing path starts (empty:
  // the working folder).
  std::string scene_folder;
  std::string initial_packing;  // Particles/initial packing as written (empty: a fill)
  std::string packing_note;     // what validate_scene read from it, for the log
  // The built-in default scene (docs/parameters.md): each entry's default is the initialiser of
  // the member it fills, but where a scene file's default differs from the plain default of the
  // engine's or the run's structs, which code that drives them uses. Those are given here once:
  // about 2,000 spheres in a 4.5 cm square box, with Young's modulus lowered from Yan and Regueiro's
  // tens of GPa (Yan and Regueiro, docs/stress.md) to 5 GPa so that the default study takes
  // minutes; a scene's run stops at rest and relaxes the bed before its final stress, and writes
  // every grid-stress formula.
  dem::SceneConfig scene = [] {
    dem::SceneConfig c;
    c.particles.material.youngs_modulus = 5e9;
    c.container.lx = c.container.ly = 0.045;
    return c;
  }();
  // Simulation/maximum steps: a run of more (end time / time step) is refused as a likely mistake.
  double maximum_steps = 1e10;
  dem::EffectSwitches
      effect_switches;  // the Effects section as written; validate_scene derives scene.effects
  OutputOptions output = [] {
    OutputOptions o;
    for (int k = 0; k < dem::kStressFormulaCount; ++k)
      o.grid_stress.formulas.push_back(static_cast<dem::StressFormula>(k));
    return o;
  }();
  RunControl control = [] {
    RunControl c;
    c.rest_ratio = 1e-6;
    c.relax_at_end = true;
    return c;
  }();
  bool overwrite = false;
  std::string stress_box = "auto";  // Stress/box as written; applied by validate_scene
  std::string collapse = "none";    // Container/collapse: none, constrained or unconstrained
  StudyOptions study;
  AccuracyOptions accuracy;        // the Accuracy section (upgrain --study accuracy)
  CalibrationOptions calibration;  // the Calibration section (upgrain --study calibration)
  ElementOptions element;          // the Element test section (upgrain --study element)
  FemxdemOptions femxdem;          // the FEMxDEM section (upgrain --study femxdem)
  ParallelInput parallel;
  // A restart (upgrain --restart): the run continues from `resume` (rank 0's; null elsewhere)
  // in its own output folder, which then holds results by design.
  bool restarting = false;
  std::shared_ptr<const Checkpoint> resume;
  // What validate_scene accepted but the user should hear, one line each (printed once).
  std::vector<std::string> warnings;
};

// Reads a .prm file: syntax and entry names first (prm_syntax.h), values by deal.II's
// ParameterHandler, then the checks across parameters (validate_scene). Throws
// upgrain::Error naming the file, line or parameter.
SceneInput read_scene_file(const std::string& filename, const StudyUse& use);

// The built-in default scene: every parameter at its default.
SceneInput default_scene(const StudyUse& use);

// A scene from the bytes of a parameter file (a checkpoint's scene, a file read by
// read_scene_bytes), decoded (scene_text.h) and checked (prm_syntax.h), with `source` naming it
// in errors; not yet validated (validate_scene).
SceneInput parse_scene_text(const std::string& text, const std::string& source);

// The entries two scenes' parameter texts (CheckpointOptions::scene) give different values,
// as "Section/entry: 'a' -> 'b'", but those a restart may change: Simulation/end time and
// maximum steps, the Checkpoint section, the Parallel section but its summation, and
// Output/folder and overwrite.
std::vector<std::string> differing_parameters(const std::string& run, const std::string& given);

// Continuum/material file (docs/calibration.md): E and nu read from the calibrated material file,
// a scene-file fragment read as a scene (its other entries are ignored), replacing the Continuum
// entries; a relative path is taken from the folder of `scene_file` (the current folder when it
// is empty). Throws upgrain::Error naming the file. read_scene_file applies it, when the command
// uses the Continuum's material (uses_continuum_material).
void apply_material_file(SceneInput& in, const std::string& scene_file);

// Which sections the study uses (docs/input.md, "Checks across parameters"), from its StudyUse;
// their checks run only then. The scene's own study compares with the continuum (Study,
// Continuum, CoarseGraining) when Study/compare with continuum is true; the accuracy study takes
// the Continuum's material for its continuum knob. The Calibration section is used by the
// calibration study, and by a comparison that calibrates its continua (Continuum/material from,
// resolved by that study's check).
bool compares_with_continuum(const SceneInput& in);
bool uses_continuum_material(const SceneInput& in);
bool calibrates(const SceneInput& in);

// Checks that involve several parameters or the file system: gradation curve, the fill
// fits the container, the time step is safe, the stress grid's box; a section's own checks only
// when `input.use` uses it; last, the study's own checks (StudyUse::check). Fills in what
// depends on several entries. Nothing is written. (The output folder is checked for a run by the
// driver: scene_limits.h, check_output_folder.)
void validate_scene(SceneInput& input);

// The annotated default parameter file, and its Markdown form for docs/parameters.md.
void print_default_parameters(std::ostream& out);
void print_parameters_markdown(std::ostream& out);

}  // namespace upgrain::coupling
