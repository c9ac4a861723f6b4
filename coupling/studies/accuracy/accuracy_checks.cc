#include "coupling/studies/accuracy/accuracy_checks.h"

#include <vector>

#include "coupling/studies/accuracy/accuracy_knobs.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

void check_accuracy_study(SceneInput& in, const std::string& where) {
  try {
    std::vector<std::string> skipped;
    (void)knob_settings(in, in.accuracy, 1, skipped);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
}

}  // namespace upgrain::coupling
