// libFuzzer target: the parameter-file reader on arbitrary bytes (docs/input.md, "Fuzzing").
// The syntax check, then the full read into a SceneInput and its validation, as the driver
// does before a run; nothing is run or written. Any input must end in upgrain::Error (a
// refusal naming the file, line or parameter) or in a scene: another exception, a crash, a
// sanitizer report or a hang is a defect.
#include <cstddef>
#include <cstdint>
#include <string>

#include "coupling/input/prm_syntax.h"
#include "coupling/input/scene_input.h"
#include "coupling/studies/accuracy/accuracy_checks.h"
#include "coupling/studies/calibration/calibration_checks.h"
#include "coupling/studies/continuum/continuum_checks.h"
#include "coupling/studies/element/element_checks.h"
#include "dem/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace upgrain;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    coupling::check_prm_syntax(text, "fuzz.prm");
  } catch (const Error&) {
  }
  try {
    const coupling::SceneInput read = coupling::parse_scene_text(text, "fuzz.prm");
    // Under each study (a row of coupling/studies/study_table.cc, whose runs this build does not
    // link): a section's checks run only when it is used (the Accuracy section's for the
    // accuracy study, the Calibration section's when the bed is calibrated).
    for (const coupling::StudyUse& use : {coupling::kContinuumUse, coupling::kAccuracyUse,
                                          coupling::kCalibrationUse, coupling::kElementUse}) {
      coupling::SceneInput in = read;
      in.use = use;
      // A folder that does not exist: validation looks at it, and nothing creates it.
      in.output.folder = "/nonexistent/upgrain-fuzz-output";
      try {
        coupling::validate_scene(in);
      } catch (const Error&) {
      }
    }
  } catch (const Error&) {
  }
  return 0;
}
