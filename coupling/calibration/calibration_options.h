#pragma once
// The Calibration section of a scene file (docs/calibration.md): how the calibration study
// (`upgrain --study calibration`) loads the bed.
#include <vector>

namespace upgrain::coupling {

struct CalibrationOptions {
  // The lid's targets as multiples of the bed's weight over the box's footprint, ascending.
  std::vector<double> lid_stress_factors = {0.5, 1.0, 2.0, 4.0};
  double hold_time = 0.05;          // s of simulated time per target
  double seating_time = 0.2;        // s for the lid to come down and seat before the first hold
  double gain_factor = 0.5;         // the servo's alpha
  double max_speed = 0.05;          // m/s
  long update_every = 10;           // steps between servo updates
  double side_wall_friction = 0.0;  // the oedometer ring's (the floor keeps the scene's)
};

}  // namespace upgrain::coupling
