#pragma once
// A deforming cell held still (L = 0) and run until its grains are in equilibrium: the
// relaxation after each increment of the FEM x DEM cell (Guo and Zhao 2014) and at the
// end of its preparation. The criterion is the unbalanced-force ratio (Yade's unbalancedForce,
// dem/engine/unbalanced_force.h), the dissipation the contact law's own dashpot: the cell's
// dynamics are the run's, only L is zero.
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

// Of the engine's last evaluation (one rank: MPI_COMM_SELF).
[[nodiscard]] double unbalanced_force_ratio(const dem::Simulation& sim);

struct HeldCellRelaxation {
  long steps = 0;
  double unbalanced_force = 0.0;  // the ratio at the end
  bool converged = false;         // unbalanced_force <= the tolerance
};

// Holds the cell (Simulation::hold_cell) and steps until the ratio is at most `tolerance` or
// `cap` steps were taken. An engine just restored from a state takes one step first (its
// contacts are recorded by a step).
HeldCellRelaxation relax_held_cell(dem::Simulation& sim, double tolerance, long cap);

}  // namespace upgrain::coupling
