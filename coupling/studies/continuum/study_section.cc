// The Study section: the DEM-vs-continuum comparison and the relaxation before it (docs/study.md).
#include "coupling/input/formula_choices.h"
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

Section study_section() {
  return {
      "Study",
      {boolean("compare with continuum", at(&SceneInput::study, &StudyOptions::compare_with_continuum),
               "After the DEM run, solve the continua of the same container (Continuum/variants) on a mesh"
               " matching the stress grid and write the comparison tables, plots and report.md "
               "(docs/study.md). False: the DEM run only."),
       subset("comparison formulas", at(&SceneInput::study, &StudyOptions::formulas),
              stress_formula_choices(),
              "DEM stress formulas set beside the continuum; each must also be in Stress/formulas."),
       boolean("relax at end", at(&SceneInput::control, &RunControl::relax_at_end),
               "Relax the deposited bed to static equilibrium by FIRE before its final stress "
               "(docs/stress.md)."),
       real("relaxation tolerance",
            at(&SceneInput::control, &RunControl::relaxation, &dem::RelaxationOptions::force_tolerance),
            1e-15, 1.0, "-",
            "FIRE stops when every grain's |F + m g| < tolerance m g and |T| < tolerance m g r."),
       integer("max relaxation steps",
               at(&SceneInput::control, &RunControl::relaxation, &dem::RelaxationOptions::max_steps), 0,
               2147483647, "-", "Upper bound on the FIRE steps; the residual reached is reported.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
