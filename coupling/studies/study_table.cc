#include "coupling/studies/study_table.h"

#include "coupling/studies/accuracy/accuracy_checks.h"
#include "coupling/studies/accuracy/accuracy_study.h"
#include "coupling/studies/calibration/calibration_checks.h"
#include "coupling/studies/calibration/calibration_study.h"
#include "coupling/studies/continuum/continuum_checks.h"
#include "coupling/studies/continuum/continuum_study.h"
#include "coupling/studies/element/element_checks.h"
#include "coupling/studies/element/element_study.h"
#include "coupling/studies/femxdem/femxdem_checks.h"
#include "coupling/studies/femxdem/femxdem_study.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

const Study kStudies[] = {
    {kContinuumUse,
     "the scene's DEM run, then, unless 'Study/compare with continuum'\n"
     "is false, the DEM-vs-continuum study (docs/study.md); the\n"
     "default",
     run_continuum_study},
    {kAccuracyUse,
     "run the accuracy study of the scene (its Accuracy section,\n"
     "docs/accuracy.md): every knob's values against wall time,\n"
     "into <Output/folder>/accuracy/",
     run_accuracy_study},
    {kCalibrationUse,
     "deposit the scene's bed and compress it under a servo lid in\n"
     "stress steps (its Calibration section, docs/calibration.md):\n"
     "the stress-strain path and the equivalent elastic material,\n"
     "into <Output/folder>/calibration/",
     run_calibration_study},
    {kElementUse,
     "compress the scene's grains in a fully periodic cell without\n"
     "gravity or walls: isotropically to each pressure, then in\n"
     "drained triaxial compression (its Element test section,\n"
     "docs/element-tests.md), into <Output/folder>/element/",
     run_element_study},
    {kFemxdemUse,
     "FEM x DEM: a biaxial specimen meshed by deal.II whose every\n"
     "Gauss point is a periodic DEM cell of the scene's grains (its\n"
     "FEMxDEM section, docs/femxdem.md), into <Output/folder>/femxdem/",
     run_femxdem_study},
};

}  // namespace

std::span<const Study> studies() { return kStudies; }

std::string study_names() {
  std::string names;
  for (const Study& s : kStudies) names += (names.empty() ? "" : ", ") + std::string(s.use.name);
  return names;
}

const Study& study_named(std::string_view name) {
  for (const Study& s : kStudies)
    if (s.use.name == name) return s;
  throw CollectiveError("--study: unknown study '" + std::string(name) + "' (known: " + study_names() + ")");
}

}  // namespace upgrain::coupling
