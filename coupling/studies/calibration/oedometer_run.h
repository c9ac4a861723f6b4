#pragma once
// The oedometric test on a bed in an engine (docs/calibration.md, "Oedometric test"), loaded
// in one of two ways:
//  - by gravity: the bed is held at its own weight for a hold time, then its weight is raised by
//    each of a list of factors in turn (a centrifuge test in silico), ramped over half a hold
//    time and held; its mean vertical stress follows from equilibrium (f W / (2 A) less the side
//    walls' share), K0 is the ratio of its Bagi stresses over the box that holds it, and its mean
//    vertical strain comes from the descent of its centre of mass (dem::centroid_vertical_strain).
//    No wall touches the top: nothing to seat;
//  - by a servo lid (coupling/run/lid.h), placed on the bed's highest grain, holding each target
//    stress for a hold time; the bed's mean stress by Bagi's formula over the box from the floor
//    to the lid (one cell), its vertical strain from the lid's travel.
// Collective over the engine's ranks; the records are the same bits on every rank and rank count
// with the deterministic summation.
#include <functional>
#include <vector>

#include "dem/analysis/oedometer.h"
#include "dem/core/types.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

// periodic_cell: the bed's grains without walls, in a periodic cell whose servo takes the lid's
// targets (periodic_cell_tests.h); run_oedometer() does not run it.
enum class OedometerLoading { gravity, lid, periodic_cell };

struct OedometerOptions {
  OedometerLoading loading = OedometerLoading::gravity;
  std::vector<double> gravity_factors;  // > 1, ascending: the bed's weight times each, in turn
  std::vector<double> lid_stresses;     // Pa, each held in turn
  double hold_time = 0.05;              // s of simulated time per target or gravity factor
  // (lid) s before the first hold in which the lid comes down onto the bed and seats at the first
  // target: the bed's top is uneven, and the lid's first contacts are impacts (not recorded).
  double seating_time = 0.1;
  double gain_factor = 0.5;
  double max_speed = 0.05;           // m/s
  long update_every = 10;            // steps
  std::function<void()> after_step;  // called after every step (a progress report)
};

struct OedometerRecord {
  double time = 0.0;
  double gravity_factor = 1.0;         // the bed's weight over its own (gravity loading)
  double target = 0.0;                 // the lid's target (0 for the unloaded bed, and by gravity)
  double lid_stress = 0.0;             // the lid's normal force over the footprint (Pa)
  double height = 0.0;                 // the lid's height above the floor, or 2 zc by gravity (m)
  double centroid = 0.0;               // zc, the bed's centre of mass's height (m)
  double side_wall_share = 0.0;        // by gravity: the side walls' lift over the bed's weight
  dem::Mat3 bagi = dem::Mat3::Zero();  // the bed's mean Bagi stress over the box (Pa, tension positive)
  dem::OedometerState state;           // compression positive (see the loading above)
  // The bed at rest under its load, so that the state enters the fit: the lid within 5 % of its
  // target; by gravity, the centre of mass moved in the last fifth of the hold by at most 2 % of
  // its settlement since the last state. State 0 is the bed as it is.
  bool at_rest = false;
};

// The bed's mean stress by Bagi's formula over the box from the floor to `height` (one cell), as
// a record's height, bagi, sigma_v = -sigma_zz and sigma_h = -(sigma_xx + sigma_yy) / 2; the rest
// zero. Needs a step that recorded its contacts. Collective.
OedometerRecord stress_below(const dem::Simulation& sim, double height);

// Record 0 is the bed under its own weight (by gravity: after a hold; by lid: the lid just
// placed, touching nothing), then one per gravity factor or lid target, at the end of its hold
// (by lid, the first after the seating).
// Throws upgrain::Error when the scene has no floor at z = 0, gravity does not point down -z
// (gravity loading), or the run fails.
std::vector<OedometerRecord> run_oedometer(dem::Simulation& sim, const OedometerOptions& o);

// The steps the test takes at time step `dt`: by gravity the holds' (one more than the factors);
// by lid the unloaded state's, the seating's and the holds'.
long oedometer_steps(const OedometerOptions& o, double dt);

}  // namespace upgrain::coupling
