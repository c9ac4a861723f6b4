#pragma once
// A deforming cell held still (L = 0) and run until its grains are in equilibrium: the
// relaxation after each increment of the FEM x DEM cell (Guo and Zhao 2014) and at the end of its
// preparation. The criterion is the unbalanced-force ratio (Yade's unbalancedForce,
// dem/engine/unbalanced_force.h). The dynamics are the run's own, damped by the contact law's
// dashpots alone, or steered by FIRE (Bitzek et al. 2006; dem/engine/relaxation.h), which turns
// the velocities towards the forces and stops every grain when the power turns negative
// (docs/femxdem.md, "Relaxing the held cell").
#include <functional>

#include "coupling/femxdem/rve_options.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

struct HeldCellRelaxation {
  long steps = 0;
  double unbalanced_force = 0.0;  // the ratio at the end
  bool converged = false;         // unbalanced_force <= the tolerance
};

// Holds the cell (Simulation::hold_cell) and steps by `method` until the ratio is at most
// `tolerance` or `cap` steps were taken; the cell stays held. An engine just restored from a
// state takes one step first (its contacts are recorded by a step). `after_step`, when set, is
// called after each step (FIRE: after its velocity mixing).
HeldCellRelaxation relax_held_cell(dem::Simulation& sim, RveRelaxation method, double tolerance, long cap,
                                   const std::function<void()>& after_step = {});

}  // namespace upgrain::coupling
