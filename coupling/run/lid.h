#pragma once
// The lid of a scene (docs/scenes.md, "Lid"): a horizontal wall placed on the bed at a given
// time, just above its highest grain, then driven down at a prescribed speed or servo-controlled
// to hold a sequence of target normal stresses (dem/boundary/servo_wall.h), each for a given
// time. The oedometric test of the calibration (docs/calibration.md) is a bed under a servo lid.
//
// The lid is a wall of the engine (Simulation::add_wall), so a checkpoint keeps it with its
// velocity, and its force history is in walls.csv. Its control is a function of the step and of
// the lid's force (the same bits on every rank): a restarted run drives it as the run it
// continues, and on any rank count alike.
#include <string>
#include <vector>

#include "coupling/run/lid_control.h"
#include "coupling/run/servo_walls.h"
#include "dem/boundary/servo_wall.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

// The lid during a run; every rank holds one alike.
class Lid {
 public:
  explicit Lid(const LidControl& control)
      : control_(control), servo_(control.gain_factor, control.max_speed, control.update_every) {}
  // Before each step (collective): places the lid when its time has come and sets its velocity
  // (the servo's every update_every steps, from the lid's normal force of the last evaluation).
  void before_step(dem::Simulation& sim);
  // The lid's wall index, or -1 before it is placed.
  [[nodiscard]] static long index(const dem::Simulation& sim);
  // The normal stress on the lid (Pa, compression positive) at the last evaluation: its normal
  // force over the container's footprint. Collective.
  [[nodiscard]] static double stress(const dem::Simulation& sim);

 private:
  const LidControl& control_;
  ServoWalls servo_;
};

// The height of the highest grain top (a bounding sphere's for ellipsoids) over every rank; -inf
// without grains. Collective.
[[nodiscard]] double highest_grain_top(const dem::Simulation& sim);

// Adds a horizontal wall named `lid` (normal -z) `gap` above the highest grain top (a bounding
// sphere's for ellipsoids) over every rank, with that Coulomb coefficient; returns its index.
// Collective; throws upgrain::Error without grains.
std::size_t place_lid(dem::Simulation& sim, double gap, double friction);

}  // namespace upgrain::coupling
