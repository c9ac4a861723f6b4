#pragma once
// The friction-angle test on a bed in an engine (docs/calibration.md, "Friction angle"): a
// triaxial-like compression of the bed in its box. Gravity is switched off (an element test: a
// uniform stress, not the bed's weight gradient), a lid is placed on the highest grain, and the
// lid and the four side walls, servo-controlled (coupling/run/servo_walls.h), consolidate the
// bed isotropically to the confining stress sigma_3. Then the lid is driven down at a constant
// speed (a constant axial strain rate of the consolidated height) while the side walls keep
// holding sigma_3, moving along their normals. At each record the sample's mean stress is taken
// by Bagi's formula over the box between the walls (one cell), its axial strain from the lid's
// travel and its volumetric strain from the box's volume. Collective over the engine's ranks;
// the records are the same bits on every rank count with the deterministic summation.
#include <array>
#include <functional>
#include <vector>

#include "dem/analysis/triaxial.h"
#include "dem/core/types.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

struct TriaxialOptions {
  double confining_stress = 0.0;     // sigma_3 (Pa)
  double strain_rate = 0.1;          // axial strain rate (1/s) of the consolidated height
  double final_strain = 0.1;         // axial strain at which the test ends
  double consolidation_time = 0.05;  // s of isotropic consolidation before the shearing
  double gain_factor = 0.5;
  double max_speed = 0.05;           // m/s, of every servo wall
  long update_every = 10;            // steps between servo updates
  int records = 100;                 // records of the shearing (besides the consolidated state)
  std::function<void()> after_step;  // called after every step (a progress report)
};

struct TriaxialRecord {
  double time = 0.0;
  double height = 0.0;                  // the lid above the floor (m)
  double width_x = 0.0, width_y = 0.0;  // between the side walls (m)
  double lid_stress = 0.0;              // the lid's normal force over the sample's footprint (Pa)
  std::array<double, 4> side_stress{};  // x-, x+, y-, y+: normal force over the wall's face (Pa)
  dem::Mat3 bagi = dem::Mat3::Zero();   // the sample's mean stress (Pa, tension positive)
  dem::TriaxialState state;             // sigma_1 = -bagi_zz, sigma_3 = -(bagi_xx + bagi_yy)/2
};

// Record 0 is the consolidated sample (the start of the strains), then `records` records evenly
// spaced in the shearing, the last at the final strain. The engine's scene must be a box
// (dem/boundary/container.h) with its floor at z = 0 and no lid; its walls' friction is theirs
// (the calibration makes them frictionless). Throws upgrain::Error when the box is not there.
std::vector<TriaxialRecord> run_triaxial(dem::Simulation& sim, const TriaxialOptions& o);

// The steps the test takes at time step `dt`: the consolidation's and the shearing's.
long triaxial_steps(const TriaxialOptions& o, double dt);

}  // namespace upgrain::coupling
