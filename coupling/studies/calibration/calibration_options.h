#pragma once
// The Calibration section of a scene file (docs/calibration.md): how the calibration study
// (`upgrain --study calibration`) loads the bed: the oedometric test and the friction-angle test,
// both from the deposited bed.
#include <string>
#include <vector>

namespace upgrain::coupling {

struct CalibrationOptions {
  // How the oedometric test loads the bed (oedometer_run.h): by raising its weight (gravity) or
  // by a servo lid.
  bool oedometer_by_lid = false;
  // Where both tests load the bed's grains: between the bed's walls (the oedometer by
  // oedometer_by_lid), or without walls, in a fully periodic cell of the bed's box whose servo
  // takes the lid's targets and the friction-angle test's sigma_3 (periodic_cell_tests.h).
  bool periodic_cell = false;
  // The bed's weight times each, in turn (gravity loading), ascending from above 1.
  std::vector<double> gravity_factors = {1.5, 2.0};
  // The lid's targets as multiples of the bed's weight over the box's footprint, ascending.
  std::vector<double> lid_stress_factors = {0.5, 1.0, 2.0, 4.0};
  double hold_time = 0.03;          // s of simulated time per target or gravity factor
  double seating_time = 0.2;        // s for the lid to come down and seat before the first hold
  double gain_factor = 0.5;         // the servo's alpha
  double max_speed = 0.05;          // m/s
  long update_every = 10;           // steps between servo updates
  double side_wall_friction = 0.0;  // the oedometer ring's (the floor keeps the scene's)
  // Whether the oedometric test gives the bed's side walls side_wall_friction (the calibration
  // study, which deposits its bed in that ring), or keeps them as the bed has them (a study's own
  // bed, deposited and relaxed between its scene's walls: without their friction it settles).
  bool lubricate_side_walls = true;
  // The friction-angle test (triaxial_run.h); the servo settings above apply to its walls too.
  double confining_stress_factor = 12.5;  // sigma_3 in units of the bed's weight over the footprint
  double axial_strain_rate = 0.375;       // 1/s
  double final_axial_strain = 0.15;
  double consolidation_time = 0.05;  // s
  // Which strength the calibrated material takes: the peak angle with the dilatancy angle at
  // the peak, or the critical-state angle with no dilatancy.
  bool critical_state_strength = false;
};

// Why `factors` are not gravity factors of the oedometric test (each > 1, ascending), or "" when
// they are. Header-only: the scene's validation takes it without the engine.
inline std::string gravity_factors_error(const std::vector<double>& factors) {
  for (std::size_t k = 0; k < factors.size(); ++k)
    if (!(factors[k] > (k == 0 ? 1.0 : factors[k - 1]))) return "the factors must be > 1 and ascending";
  return "";
}

}  // namespace upgrain::coupling
