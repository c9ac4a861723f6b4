#pragma once
// Servo-controlled walls on an engine (docs/calibration.md, "Servo wall"): each update, every
// servo wall's velocity along its normal is set from its normal stress, its target and the
// Hertz stiffness bound of its contacts (dem/boundary/servo_wall.h). The lid of a scene
// (coupling/run/lid.h) is one such wall; the triaxial test's side walls and platen are others
// (coupling/studies/calibration/triaxial_run.h). Collective over the engine's ranks; the velocities are
// functions of exact wall forces and counts, so the same bits on every rank count.
#include <cstddef>
#include <vector>

#include "dem/boundary/servo_wall.h"
#include "dem/core/types.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

struct ServoWall {
  std::size_t wall = 0;        // index in Simulation::walls()
  double target_stress = 0.0;  // Pa, compression positive
  double area = 0.0;           // m^2 the wall's normal force is spread over
};

// A wall's normal stress (Pa, compression positive) from its force (Simulation::wall_forces()).
double wall_normal_stress(const dem::PlaneWall& wall, const dem::Vec3& force, double area);

// The servo of a set of walls. Keeps the largest Hertz radius a wall can see, taken once.
class ServoWalls {
 public:
  // integral_factor: beta of dem::servo_speed_with_integral (0: the proportional servo).
  ServoWalls(double gain_factor, double max_speed, long update_every, double integral_factor = 0.0)
      : gain_factor_(gain_factor),
        max_speed_(max_speed),
        update_every_(update_every),
        beta_(integral_factor) {}
  // Sets each wall's velocity (speed times its inward normal) when the step count is a multiple
  // of update_every, from the forces of the last evaluation. Collective.
  void update(dem::Simulation& sim, const std::vector<ServoWall>& walls);

 private:
  double gain_factor_, max_speed_;
  long update_every_;
  double beta_;
  double r_max_ = 0.0;
  std::vector<double> integral_;  // per wall index: the integral term's speed (m/s)
};

}  // namespace upgrain::coupling
