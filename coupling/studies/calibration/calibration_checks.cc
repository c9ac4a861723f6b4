#include "coupling/studies/calibration/calibration_checks.h"

#include <array>
#include <sstream>

#include "dem/core/error.h"

namespace upgrain::coupling {

std::string calibration_refusal(const SceneInput& in) {
  const std::array<bool, 3>& periodic = in.scene.container.periodic;
  if (in.calibration.periodic_cell) {
    // Without servo walls: any law; the bed needs its floor.
    if (periodic[2])
      return "the calibration's periodic cell is the box of a bed on its floor; a scene periodic along z "
             "(Container/periodic axes) has no floor";
    if (in.scene.container.has_gate() || in.scene.container.opens_side_walls())
      return "the calibration's periodic cell is the box of a bed deposited in it; a scene with a gate or "
             "with "
             "side walls that open (Container) is not one";
    return "";
  }
  if (in.scene.contact_law != "hertz-mindlin")
    return "the calibration's servo walls need Contact/law = hertz-mindlin, not " + in.scene.contact_law;
  if (in.scene.container.has_gate() || in.scene.container.opens_side_walls())
    return "the calibration's tests load the bed in its closed box; a scene with a gate or with side walls "
           "that "
           "open (Container) is not one";
  if (periodic[0] || periodic[1] || periodic[2])
    return "the calibration's tests load the bed between walls; a scene with Container/periodic axes is not "
           "one (the periodic element tests are upgrain --study element: docs/element-tests.md)";
  if (!in.calibration.oedometer_by_lid && !(in.scene.effects.gravity && in.scene.gravity > 0.0))
    return "the oedometric test by gravity (Calibration/oedometer loading) raises the bed's weight, and this "
           "scene has none (Effects/gravity)";
  return "";
}

void check_calibration(const SceneInput& in, const std::string& where) {
  const dem::SceneConfig& s = in.scene;
  // Each oedometric loading has its own entries (Calibration/oedometer loading).
  const bool by_lid = in.calibration.oedometer_by_lid || in.calibration.periodic_cell;
  if (!by_lid) {
    const std::vector<double>& f = in.calibration.gravity_factors;
    if (f.empty())
      throw Error(where +
                  "Calibration/gravity factors: give at least one factor (a modulus needs two states)");
    if (const std::string why = gravity_factors_error(f); !why.empty())
      throw Error(where + "Calibration/gravity factors: " + why);
  }
  if (by_lid) {
    const std::vector<double>& f = in.calibration.lid_stress_factors;
    if (f.size() < 2)
      throw Error(where +
                  "Calibration/lid stresses: give at least two targets (a modulus needs two loaded states)");
    for (std::size_t k = 0; k < f.size(); ++k)
      if (!(f[k] > 0.0) || (k > 0 && !(f[k] > f[k - 1])))
        throw Error(where + "Calibration/lid stresses: the targets must be > 0 and ascending");
  }
  {
    // The friction-angle test's shearing records 100 states: it needs at least one step each.
    const CalibrationOptions& c = in.calibration;
    const double shearing = c.final_axial_strain / c.axial_strain_rate;
    if (shearing < 100.0 * s.time_step) {
      std::ostringstream m;
      m << where << "Calibration/final axial strain / axial strain rate = " << shearing
        << " s of shearing is shorter than 100 time steps (" << 100.0 * s.time_step
        << " s): the friction-angle test records 100 states; lower Calibration/axial strain rate";
      throw Error(m.str());
    }
    if (!c.periodic_cell && c.consolidation_time < 10.0 * static_cast<double>(c.update_every) * s.time_step) {
      std::ostringstream m;
      m << where << "Calibration/consolidation time = " << c.consolidation_time
        << " s gives the servo walls fewer than 10 updates (Calibration/update interval = " << c.update_every
        << " steps of " << s.time_step << " s)";
      throw Error(m.str());
    }
  }
}

void check_calibration_study(SceneInput& in, const std::string& where) {
  if (const std::string why = calibration_refusal(in); !why.empty())
    throw Error(where + "--study calibration: " + why + " (docs/calibration.md)");
  check_calibration(in, where);
}

}  // namespace upgrain::coupling
