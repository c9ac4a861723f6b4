#pragma once
// The knobs of an accuracy study (docs/accuracy.md): each a setting of the scene that trades
// accuracy for time, with the values to try. A setting changes a copy of the scene's input
// and nothing else; the study runs it and compares what a user reads off the bed.
#include <functional>
#include <string>
#include <vector>

#include "coupling/input/scene_input.h"
#include "coupling/studies/accuracy/accuracy_options.h"

namespace upgrain::coupling {

// How a setting is evaluated.
enum class SettingRun {
  dem,           // a DEM run of the changed scene, on every rank
  dem_one_rank,  // the same on rank 0 alone (the rank-count knob)
  fem,           // the continuum alone, against its analytic solution
};

struct KnobSetting {
  std::string knob;         // its name, as in Accuracy/knobs
  std::string label;        // the setting, as a reader says it ("0.25 of the safe step")
  double value = 0.0;       // the number a plot shows it at
  bool is_default = false;  // the scene's own setting of this knob
  SettingRun run = SettingRun::dem;
  std::function<void(SceneInput&)> apply;
  unsigned fem_degree = 0, fem_refinements = 0;  // SettingRun::fem
};

// The knob names a study knows, in the order it runs them.
const std::vector<std::string>& knob_names();

// Every setting of the chosen knobs for `base` (validated). Knobs that do not apply to the
// scene (the shape of a scene of spheres, the rank count on one rank) are named in `skipped`,
// with the reason. Throws upgrain::Error naming the knob or value when one is not valid.
std::vector<KnobSetting> knob_settings(const SceneInput& base, const AccuracyOptions& options, int ranks,
                                       std::vector<std::string>& skipped);

}  // namespace upgrain::coupling
