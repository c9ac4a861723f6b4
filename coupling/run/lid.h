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

#include "dem/boundary/servo_wall.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

inline constexpr const char* kLidWallName = "lid";

struct LidControl {
  enum class Mode { none, velocity, servo };
  Mode mode = Mode::none;
  double place_time = 0.0;  // s of simulated time
  double gap = 0.0;         // m between the highest grain's top and the lid when it is placed
  double friction = 0.0;    // Coulomb coefficient particle-lid
  double speed = 0.0;       // m/s downwards (velocity mode)
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

// The lid during a run; every rank holds one alike.
class Lid {
 public:
  explicit Lid(const LidControl& control) : control_(control) {}
  // Before each step (collective): places the lid when its time has come and sets its velocity
  // (the servo's every update_every steps, from the lid's normal force of the last evaluation).
  void before_step(dem::Simulation& sim);
  // The lid's wall index, or -1 before it is placed.
  [[nodiscard]] static long index(const dem::Simulation& sim);
  // The normal stress on the lid (Pa, compression positive) at the last evaluation: its normal
  // force over the container's footprint. Collective.
  [[nodiscard]] static double stress(const dem::Simulation& sim);

 private:
  void place(dem::Simulation& sim);
  const LidControl& control_;
  // The Hertz stiffness bound's largest radius (servo_wall.h), taken when first needed.
  double r_max_ = 0.0;
};

}  // namespace upgrain::coupling
