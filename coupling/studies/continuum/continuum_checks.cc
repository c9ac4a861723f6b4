#include "coupling/studies/continuum/continuum_checks.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "coupling/studies/calibration/calibration_checks.h"
#include "dem/core/error.h"
#include "dem/scene/insertion.h"

namespace upgrain::coupling {

namespace {

// Continuum/material from (docs/study.md): whether the study calibrates its continua on its
// own bed. A material file, when set, supplies the values instead; `calibration` beside a file,
// `entries` beside a file, and `calibration` on a bed the tests cannot load are refused; `auto`
// falls back to the entries and keeps the reason for the printout and the report.
void resolve_material_source(SceneInput& in, const std::string& where) {
  ContinuumOptions& c = in.study.continuum;
  c.calibrate_in_study = false;
  c.calibration_skipped.clear();
  if (!c.material_file.empty()) {
    if (c.material_from != ContinuumOptions::MaterialSource::automatic)
      throw Error(where + "Continuum/material from = " + c.material_from_entry() +
                  " contradicts Continuum/material file = " + c.material_file +
                  ", which supplies the values itself; set one of the two");
    return;
  }
  if (c.material_from == ContinuumOptions::MaterialSource::entries) return;
  // The study's bed is the scene's, lid included; the calibration places its own.
  const std::string why =
      in.control.lid.enabled()
          ? "the calibration places its own lid on the bed, and the scene has one (Lid section)"
          : calibration_refusal(in);
  if (why.empty()) {
    c.calibrate_in_study = true;
    return;
  }
  if (c.material_from == ContinuumOptions::MaterialSource::calibration)
    throw Error(where + "Continuum/material from = calibration: " + why +
                "; set it to entries, or to auto (docs/calibration.md)");
  c.calibration_skipped = why;
}

}  // namespace

void check_continuum_study(SceneInput& in, const std::string& where) {
  const dem::SceneConfig& s = in.scene;
  if (!compares_with_continuum(in)) return;
  {
    resolve_material_source(in, where);
    if (in.study.formulas.empty())
      throw Error(where +
                  "Study/comparison formulas is empty; name at least one formula, or set "
                  "'Study/compare with continuum = false'");
    for (dem::StressFormula f : in.study.formulas) {
      const auto& written = in.output.grid_stress.formulas;
      if (std::find(written.begin(), written.end(), f) == written.end())
        throw Error(where + "Study/comparison formulas names '" + std::string(dem::name_of(f)) +
                    "', which is not in Stress/formulas; add it there");
    }
  }
  if (calibrates(in)) check_calibration(in, where);
  {
    // The coarse-grained fields live on the study's mesh; what the run keeps for them, and
    // the section's checks only when the study captures them.
    const CoarseGrainingOptions& cg = in.study.coarse_graining;
    CoarseGrainingCapture& capture = in.output.coarse_graining;
    capture.enabled = cg.any();
    capture.displacement = cg.displacement;
    capture.reference_time = cg.reference_time;
    capture.later_steps = 0;
  }
  if (const CoarseGrainingCapture& capture = in.output.coarse_graining; capture.enabled) {
    const CoarseGrainingOptions& cg = in.study.coarse_graining;
    if (cg.reference_time > s.end_time) {
      std::ostringstream m;
      m << where << "CoarseGraining/reference time = " << cg.reference_time
        << " s is after Simulation/end time = " << s.end_time
        << " s: the displacement would have no reference";
      throw Error(m.str());
    }
    if (cg.by_differences && cg.sampling_interval > 0.0 && cg.sampling_interval < 0.5 * s.time_step) {
      std::ostringstream m;
      m << where << "CoarseGraining/sampling interval = " << cg.sampling_interval
        << " s is shorter than half a time step (" << s.time_step << " s); give at least one time step, or 0";
      throw Error(m.str());
    }
    if (cg.displacement && s.insertion.enabled()) {
      // The displacement is measured from each grain's position at the reference time: a grain
      // poured after it has none (docs/insertion.md).
      const double last = dem::last_batch_time(s, dem::plan_pour(s));
      if (cg.reference_time <= last) {
        std::ostringstream m;
        m << where << "CoarseGraining/reference time = " << cg.reference_time
          << " s is not after the pour's last batch (t = " << last
          << " s, Insertion; later if the inlet holds batches back): the grains poured later have no "
             "reference "
             "position for the displacement; set a later reference time, or leave displacement out of "
             "CoarseGraining/fields";
        throw Error(m.str());
      }
    }
    in.output.coarse_graining.later_steps =
        cg.by_differences ? std::max(1L, std::lround(cg.sampling_interval / s.time_step)) : 0L;
  }
}

}  // namespace upgrain::coupling
