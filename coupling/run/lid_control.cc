#include "coupling/run/lid_control.h"

#include <algorithm>
#include <cmath>

#include "dem/boundary/servo_wall.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

double LidControl::target_at(double t) const {
  if (target_stresses.empty()) return 0.0;
  const double k = step_duration > 0.0 ? std::floor((t - place_time) / step_duration) : 0.0;
  const auto last = static_cast<double>(target_stresses.size() - 1);
  return target_stresses[static_cast<std::size_t>(std::clamp(k, 0.0, last))];
}

void validate_lid(const LidControl& lid, const dem::SceneConfig& scene) {
  if (!lid.enabled()) return;
  if (lid.place_time >= scene.end_time)
    throw Error("Lid/place time (" + std::to_string(lid.place_time) +
                " s) must be before Simulation/end time (" + std::to_string(scene.end_time) + " s)");
  if (lid.mode == LidControl::Mode::velocity && !(lid.speed != 0.0))
    throw Error("Lid/mode = velocity needs a non-zero Lid/speed");
  if (lid.mode != LidControl::Mode::servo) return;
  if (lid.target_stresses.empty())
    throw Error("Lid/mode = servo needs Lid/target stresses (Pa, comma-separated)");
  for (double s : lid.target_stresses)
    if (!std::isfinite(s) || s <= 0.0)
      throw Error("Lid/target stresses: every target must be > 0 Pa, not " + std::to_string(s));
  if (lid.target_stresses.size() > 1 && !(lid.step_duration > 0.0))
    throw Error("Lid/step duration must be > 0 s with more than one target stress");
  if (scene.contact_law != "hertz-mindlin")
    throw Error(
        "Lid/mode = servo: the servo's gain bounds the lid's stiffness for Hertz contacts; Contact/law = " +
        scene.contact_law + " is not supported (docs/calibration.md)");
  // The gain factor and the speed: the kernel's own checks, named by their entries.
  try {
    dem::check_servo_settings({lid.target_stresses.front(), 1.0, lid.gain_factor, lid.max_speed});
  } catch (const Error& e) {
    throw Error(std::string("Lid/gain factor or Lid/max speed: ") + e.what());
  }
}

}  // namespace upgrain::coupling
