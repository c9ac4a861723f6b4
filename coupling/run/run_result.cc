#include "coupling/run/run_result.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dem/files/json_number.h"

namespace upgrain::coupling {

namespace {
std::string num(double v) { return dem::io::json_number(v); }
// A JSON string (the names written here need no escapes).
std::string quoted(std::string s) {
  s.insert(s.begin(), '"');
  s.push_back('"');
  return s;
}
std::string steps_list(const std::vector<long>& steps) {
  std::string a = "[";
  for (std::size_t k = 0; k < steps.size(); ++k) a += (k ? ", " : "") + std::to_string(steps[k]);
  return a + "]";
}
}  // namespace

void measure_final_state(dem::Simulation& sim, double wall_seconds, long steps_taken, RunResult& r) {
  sim.check_finite();
  r.wall_seconds = wall_seconds;
  r.steps = sim.step_count();
  r.simulated_time = sim.time();
  r.particle_steps_per_second = static_cast<double>(steps_taken) * static_cast<double>(sim.particle_count()) /
                                std::max(r.wall_seconds, 1e-9);
  r.energy = sim.energy();
  r.energy_balance_error = dem::balance_error(sim.initial_energy(), r.energy);
  r.potential_released = sim.initial_energy().potential - r.energy.potential;
  r.kinetic_to_released = dem::kinetic_to_released(sim.initial_energy(), r.energy);
  r.diagnostics = sim.diagnostics();
  r.load = sim.load();
  r.wall_forces = sim.wall_forces();
  for (const dem::PlaneWall& w : sim.walls()) r.wall_names.push_back(w.name);
  const dem::ParticleStore& all = sim.whole_state();
  sim.on_root([&] {
    r.bed = dem::measure_bed(all, sim.scene().container);
    for (std::size_t i = 0; i < all.size(); ++i) r.total_mass += all.mass(i);
  });
}

std::vector<SideWallContact> side_wall_contacts(const dem::Simulation& sim) {
  std::vector<SideWallContact> out;
  for (const dem::ContactRecord& c : sim.gather_contacts_by_id(/*walls_only=*/true)) {
    const auto wall = static_cast<int>(-1 - c.b);
    if (!dem::is_side_wall(sim.walls()[static_cast<std::size_t>(wall)].name)) continue;
    out.push_back({wall, c.point[2], dem::get(c.force)});
  }
  return out;
}

std::map<std::string, std::string> summary_entries(const dem::Simulation& sim, const RunResult& r,
                                                   const std::vector<dem::EffectChoice>& effects) {
  const auto n = static_cast<double>(sim.particle_count());
  std::map<std::string, std::string> entries = {
      {"particles", num(n)},
      {"mpi_ranks", num(sim.ranks())},
      {"summation", quoted(dem::to_string(sim.summation()))},
      {"effects", dem::effects_json(effects)},
      {"load_rebalances", num(static_cast<double>(r.load.rebalances))},
      {"load_owned_imbalance", num(r.load.owned_imbalance)},
      {"load_compute_imbalance", num(r.load.compute_imbalance)},
      {"load_communication_share", num(r.load.communication_share)},
      {"steps", num(static_cast<double>(r.steps))},
      {"simulated_time_s", num(r.simulated_time)},
      {"wall_time_s", num(r.wall_seconds)},
      {"segment_wall_time_s", num(r.segment_seconds)},
      {"resumed_at_steps", steps_list(r.history.resumed_at)},
      {"particle_steps_per_second", num(r.particle_steps_per_second)},
      {"stopped_at_rest", r.stopped_at_rest ? "true" : "false"},
      {"kinetic_energy_J", num(r.energy.kinetic())},
      {"potential_energy_released_J", num(r.potential_released)},
      {"kinetic_to_released", num(r.kinetic_to_released)},
      {"energy_balance_error", num(r.energy_balance_error)},
      {"dissipated_damping_J", num(r.energy.dissipated_damping)},
      {"dissipated_friction_J", num(r.energy.dissipated_friction)},
      {"tangential_stiffness_change_J", num(r.energy.tangential_stiffness_change)},
      {"contacts_per_particle", num(2.0 * static_cast<double>(r.diagnostics.particle_contacts) / n)},
      {"wall_contacts", num(static_cast<double>(r.diagnostics.wall_contacts))},
      {"max_overlap_ratio", num(r.diagnostics.max_overlap_ratio)},
      {"bed_surface_height_m", num(r.bed.surface_height)},
      {"bed_solid_fraction", num(r.bed.solid_fraction)},
      {"particles_outside_container", num(static_cast<double>(r.bed.particles_outside))},
      {"relaxed", r.relaxation ? "true" : "false"},
      // null when no relaxation ran: neither converged nor not.
      {"relaxation_converged", r.relaxation ? (r.relaxation->converged ? "true" : "false") : "null"},
      {"relaxation_steps", num(r.relaxation ? static_cast<double>(r.relaxation->steps) : 0.0)},
      {"relaxation_force_residual", num(r.relaxation ? r.relaxation->max_force_residual : 0.0)},
      {"relaxation_torque_residual", num(r.relaxation ? r.relaxation->max_torque_residual : 0.0)},
  };
  if (const dem::InsertionSpec& in = sim.scene().insertion; in.enabled()) {
    entries["inserted_particles"] = num(static_cast<double>(r.inserted));
    entries["insertion_target"] = num(static_cast<double>(in.count));
  }
  return entries;
}

}  // namespace upgrain::coupling
