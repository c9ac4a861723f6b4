#include "coupling/femxdem/held_cell.h"

#include <span>

#include "dem/engine/unbalanced_force.h"

namespace upgrain::coupling {

double unbalanced_force_ratio(const dem::Simulation& sim) {
  const std::span<const dem::Vec3> forces(sim.particles().force.data(),
                                          static_cast<std::size_t>(sim.owned()));
  return dem::unbalanced_force_ratio(forces, sim.contacts());
}

HeldCellRelaxation relax_held_cell(dem::Simulation& sim, double tolerance, long cap) {
  sim.hold_cell(true);
  HeldCellRelaxation r;
  if (!sim.contacts_recorded()) {
    sim.step();
    ++r.steps;
  }
  r.unbalanced_force = unbalanced_force_ratio(sim);
  while (r.unbalanced_force > tolerance && r.steps < cap) {
    sim.step();
    ++r.steps;
    r.unbalanced_force = unbalanced_force_ratio(sim);
  }
  r.converged = r.unbalanced_force <= tolerance;
  return r;
}

}  // namespace upgrain::coupling
