#pragma once
// The settings of a scene's lid (docs/scenes.md, "Lid") and their checks, apart from the lid's
// run (coupling/run/lid.h), so that reading and validating a scene needs no engine.
#include <cstddef>
#include <string>
#include <vector>

#include "dem/scene/scene_config.h"

namespace upgrain::coupling {

inline constexpr const char* kLidWallName = "lid";

struct LidControl {
  enum class Mode { none, velocity, servo };
  Mode mode = Mode::none;
  double place_time = 0.0;  // s of simulated time
  double gap = 0.0;         // m between the highest grain's top and the lid when it is placed
  double friction = 0.0;    // Coulomb coefficient particle-lid
  double speed = 0.01;      // m/s downwards (velocity mode)
  // Servo mode: the targets (Pa, compression positive), each held for step_duration after the
  // placement, the last one to the end; the gain factor alpha and the maximum speed.
  std::vector<double> target_stresses;
  double step_duration = 0.0;
  double gain_factor = 0.5;
  double max_speed = 0.01;
  long update_every = 10;  // steps between servo updates (the gain takes the update's interval)

  [[nodiscard]] bool enabled() const { return mode != Mode::none; }
  // The target at time t (servo mode; t after the placement).
  [[nodiscard]] double target_at(double t) const;
  // The end of target k's hold: place_time + (k + 1) step_duration.
  [[nodiscard]] double step_end(std::size_t k) const {
    return place_time + static_cast<double>(k + 1) * step_duration;
  }
};

// Checks a lid's settings against its scene's end time and contact law; throws upgrain::Error
// naming the Lid entry.
void validate_lid(const LidControl& lid, const dem::SceneConfig& scene);

}  // namespace upgrain::coupling
