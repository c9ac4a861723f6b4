#pragma once
// What a study uses of a scene (docs/architecture.md, "How to add a study"). The input layer
// reads and checks a scene for the study the command line names, and knows no study's code:
// the study's row in the table (coupling/studies/study_table.h) hands it this.
#include <string>
#include <string_view>

namespace upgrain::coupling {

struct SceneInput;

struct StudyUse {
  // As `upgrain --study` takes it; empty for a plain DEM run of the scene (a study's own runs).
  std::string_view name;
  // The scene's own study: its Study, Continuum and CoarseGraining sections, when
  // Study/compare with continuum is true (docs/study.md).
  bool scene_study = false;
  // Reads the Continuum section's material without that comparison (the accuracy study's
  // continuum knob): Continuum/material file is applied.
  bool continuum_material = false;
  // Deposits with the scene's Lid; the calibration places its own (docs/calibration.md).
  bool scene_lid = true;
  // Always loads the bed in the calibration's tests (Calibration section).
  bool calibrates = false;
  // Writes the Checkpoint section's checkpoints (docs/restart.md): of its DEM runs, or of its own
  // state (own_state); the element study drives its own cells, which they do not reach.
  bool checkpoints = true;
  // Its checkpoints hold its own state (StudyState, coupling/run/checkpoint.h), not a DEM run's:
  // the FEM x DEM study's solver and cells (docs/femxdem.md). Only it continues them.
  bool own_state = false;
  // Runs the scene's own DEM run: its particle count, end time and effects. The FEM x DEM study
  // prepares its own DEM cells instead (docs/femxdem.md), and prints their effects.
  bool runs_scene = true;
  // The study's own checks, after every section's and the scene's (validate_scene). Throws
  // upgrain::Error prefixed by `where`. Null: none.
  void (*check)(SceneInput& in, const std::string& where) = nullptr;
};

}  // namespace upgrain::coupling
