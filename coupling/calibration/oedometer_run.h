#pragma once
// The oedometric test on a bed in an engine (docs/calibration.md, "Oedometric test"): a servo
// lid (coupling/run/lid.h) is placed on the bed's highest grain and holds each target stress
// for a hold time; at the end of each hold the bed's mean stress is taken by Bagi's formula over
// the box from the floor to the lid (one cell), and its vertical strain from the lid's travel.
// Collective over the engine's ranks; the records are the same bits on every rank and rank count
// with the deterministic summation.
#include <functional>
#include <vector>

#include "dem/analysis/oedometer.h"
#include "dem/core/types.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

struct OedometerOptions {
  std::vector<double> lid_stresses;  // Pa, each held in turn
  double hold_time = 0.05;           // s of simulated time per target
  // s before the first hold in which the lid comes down onto the bed and seats at the first
  // target: the bed's top is uneven, and the lid's first contacts are impacts (not recorded).
  double seating_time = 0.1;
  double gain_factor = 0.5;
  double max_speed = 0.05;           // m/s
  long update_every = 10;            // steps
  std::function<void()> after_step;  // called after every step (a progress report)
};

struct OedometerRecord {
  double time = 0.0;
  double target = 0.0;                 // the lid's target (0 for the unloaded bed)
  double lid_stress = 0.0;             // the lid's normal force over the footprint (Pa)
  double height = 0.0;                 // the lid's height above the floor (m)
  dem::Mat3 bagi = dem::Mat3::Zero();  // the bed's mean stress (Pa, tension positive)
  dem::OedometerState state;           // from the Bagi stress; strain from the lid's first height
};

// Record 0 is the bed as it is (the lid just placed, touching nothing), then one per target, at
// the end of its hold (the first after the seating).
// Throws upgrain::Error when the scene has no floor at z = 0 or the run fails.
std::vector<OedometerRecord> run_oedometer(dem::Simulation& sim, const OedometerOptions& o);

// The steps the test takes at time step `dt`: the unloaded state's, the seating's, the holds'.
long oedometer_steps(const OedometerOptions& o, double dt);

}  // namespace upgrain::coupling
