#pragma once
// The calibration's two tests on the bed's grains without its walls (docs/calibration.md, "In a
// periodic cell"): the deposited bed's grains, at rest, in a fully periodic cell of its box (the
// footprint, and the height of its highest point), without gravity; the cell's servo loads them
// (docs/periodic.md, "A cell that deforms"), and the stress is the cell's Love–Weber average.
//   oedometric test: x and y held still, z servo-controlled to each target in turn (seated at the
//     first, not recorded, then each held): the counterpart of the lid in a lubricated ring, with
//     no wall to carry a share of the load or to order the grains next to it;
//   friction-angle test: every axis servo-controlled to sigma_3 for the consolidation time, then
//     drained triaxial compression, x and y holding sigma_3, z shortened at the axial strain rate
//     (a true strain rate: L_zz = -rate) to the final axial strain.
// Both start from the same bed. The records are those of the walled tests (oedometer_run.h,
// triaxial_run.h), so that the fits, the tables and the material file are the same code; the
// walls' columns are NaN. Collective over the communicator; the same bits on any rank count with
// the deterministic summation.
#include <mpi.h>

#include <vector>

#include "coupling/studies/calibration/oedometer_run.h"
#include "coupling/studies/calibration/triaxial_run.h"
#include "dem/engine/engine_state.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

// The cell's servo: L_dd = gain (p_dd - p*) / p*, bounded by max_rate (cell_motion.h); the
// element tests' (Element test/servo gain, max strain rate).
struct CellServo {
  double gain = 0.0;      // 1/s
  double max_rate = 0.0;  // 1/s
};

// State 0 of the oedometric test: the deposited bed in its box under its own weight, its mean
// Bagi stress over the box from the floor to its highest point (the lid's state 0: K0 of the bed
// as it was deposited), and that height, the cell's. Collective.
OedometerRecord deposited_state(const dem::SceneConfig& scene, const dem::EngineState& bed, MPI_Comm comm,
                                const dem::EngineOptions& engine);

// The oedometric test in the cell of height `height` (deposited_state's): state 0 is `deposited`,
// then one state per lid target of `o` (lid_stresses, seating_time, hold_time): sigma_v = -sigma_zz,
// sigma_h = -(sigma_xx + sigma_yy) / 2 of the cell, averaged over the last quarter of the hold;
// the vertical strain 1 - h_z / height; at rest when sigma_v is within 5 % of the target.
std::vector<OedometerRecord> run_cell_oedometer(const dem::SceneConfig& scene, const dem::EngineState& bed,
                                                const OedometerRecord& deposited, const OedometerOptions& o,
                                                const CellServo& servo, MPI_Comm comm,
                                                const dem::EngineOptions& engine);

// The friction-angle test in the cell: record 0 the consolidated cell, then x.records records.
std::vector<TriaxialRecord> run_cell_triaxial(const dem::SceneConfig& scene, const dem::EngineState& bed,
                                              double height, const TriaxialOptions& x, const CellServo& servo,
                                              MPI_Comm comm, const dem::EngineOptions& engine);

// The steps each test takes at time step dt.
long cell_oedometer_steps(const OedometerOptions& o, double dt);
long cell_triaxial_steps(const TriaxialOptions& x, double dt);

}  // namespace upgrain::coupling
