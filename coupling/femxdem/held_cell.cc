#include "coupling/femxdem/held_cell.h"

#include "dem/engine/relaxation.h"
#include "dem/engine/unbalanced_force.h"

namespace upgrain::coupling {

HeldCellRelaxation relax_held_cell(dem::Simulation& sim, RveRelaxation method, double tolerance, long cap,
                                   const std::function<void()>& after_step) {
  sim.hold_cell(true);
  HeldCellRelaxation r;
  if (method == RveRelaxation::fire) {
    dem::RelaxationOptions o;
    o.measure = dem::EquilibriumMeasure::unbalanced_force;
    o.force_tolerance = tolerance;
    o.max_steps = cap;
    if (after_step) o.on_step = [&](const dem::RelaxationResult&) { after_step(); };
    const dem::RelaxationResult f = dem::relax_to_equilibrium(sim, o);
    sim.hold_cell(true);
    return {f.steps, f.unbalanced_force, f.converged};
  }
  const auto step = [&] {
    sim.step();
    ++r.steps;
    if (after_step) after_step();
  };
  if (!sim.contacts_recorded()) step();
  r.unbalanced_force = dem::unbalanced_force_ratio(sim);
  while (r.unbalanced_force > tolerance && r.steps < cap) {
    step();
    r.unbalanced_force = dem::unbalanced_force_ratio(sim);
  }
  r.converged = r.unbalanced_force <= tolerance;
  return r;
}

}  // namespace upgrain::coupling
