#include "dem/deposition.h"

#include <chrono>
#include <cmath>
#include <sstream>
#include <utility>

#include "dem/boundary/wall_release.h"
#include "dem/io/compute_grid_stress_output.h"
#include "dem/parallel/exchange.h"
#include "dem/scene/fill.h"

namespace upgrain::dem {

namespace {
// JSON has no NaN: a quantity that was not computed (energy channels without energy
// tracking) is null.
std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// The grid of an evaluation (io::stress_grid of the whole state), the same on every rank: the
// box of a moving grid needs the top (and extent) of the whole assembly, which rank 0 finds on
// the gathered state.
RegularGrid stress_grid(Simulation& sim, const io::GridStressOptions& options, const BoxContainer& box) {
  RegularGrid g;
  const ParticleStore& all = sim.whole_state();
  if (sim.is_root()) g = io::stress_grid(options, all, box);
  MPI_Bcast(g.n, 3, MPI_INT, 0, sim.comm());
  MPI_Bcast(g.lo.data(), 3, MPI_DOUBLE, 0, sim.comm());
  MPI_Bcast(g.hi.data(), 3, MPI_DOUBLE, 0, sim.comm());
  return g;
}

}  // namespace

DepositionResult run_deposition(const SceneConfig& scene, const RunControl& control,
                                const std::optional<io::OutputOptions>& output,
                                const std::function<void(const Progress&)>& on_progress, MPI_Comm comm,
                                const EngineOptions& options) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  ParticleStore fill;
  std::string error;
  if (rank == 0) {
    try {
      fill = fill_container(scene);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  throw_if_any(comm, error);
  Simulation sim(scene, std::move(fill), comm, options);
  return run_deposition(sim, scene, control, output, on_progress);
}

DepositionResult run_deposition(Simulation& sim, const SceneConfig& scene, const RunControl& control,
                                const std::optional<io::OutputOptions>& output,
                                const std::function<void(const Progress&)>& on_progress) {
  using Clock = std::chrono::steady_clock;
  const long total = static_cast<long>(std::llround(scene.end_time / scene.time_step));
  auto every = [&](double interval) {
    return interval > 0.0 ? std::max(1L, static_cast<long>(std::llround(interval / scene.time_step))) : total;
  };
  const long series_every = every(output ? output->series_interval : 0.002);
  const long snapshot_every = every(output ? output->snapshot_interval : 0.0);

  // Output is written by the root; the quantities it needs are collective (engine/simulation.h).
  std::optional<io::RunRecorder> recorder;
  auto record_series = [&] {
    const EnergyBalance e = sim.energy();
    const StepDiagnostics d = sim.diagnostics();
    sim.on_root([&] {
      recorder->record_series(sim.time(), sim.step_count(), e, balance_error(sim.initial_energy(), e), d);
    });
  };
  auto write_snapshot = [&] {
    sim.check_finite();
    const std::vector<Vec3> forces = sim.wall_forces();
    const ParticleStore& all = sim.whole_state();
    sim.on_root([&] { recorder->write_snapshot(all, sim.walls(), forces, sim.time(), sim.step_count()); });
  };
  if (output) {
    sim.on_root([&] { recorder.emplace(*output); });
    record_series();
    write_snapshot();
  }

  // Grid stress needs the contacts of a force evaluation, which are recorded on request
  // before the step that computes them (Simulation::request_contacts()).
  DepositionResult r;
  std::optional<io::GridStressRecorder> stress_out;
  std::optional<io::ComputeGridStressRecorder> compute_grid_out;  // MPI runs: per block
  const bool stress_on = output && output->grid_stress.enabled();
  if (stress_on) sim.on_root([&] { stress_out.emplace(output->folder, output->grid_stress.formulas); });
  const long stress_every =
      stress_on ? (output->grid_stress.interval > 0.0 ? every(output->grid_stress.interval) : snapshot_every)
                : 0;
  auto stress_due = [&](long s) { return stress_on && (s % stress_every == 0 || s == total); };
  // Grid strain goes with the grid stress, on its grid. The reference state (positions by
  // global id at t0) is kept in memory on the root: the initial state when t0 = 0, otherwise
  // the first evaluation at or after t0, which is then also the first strain written (F = 1).
  std::optional<io::GridStrainRecorder> strain_out;
  const bool strain_on = stress_on && output->grid_strain.enabled;
  if (strain_on) sim.on_root([&] { strain_out.emplace(output->folder); });
  std::optional<StrainReference> strain_reference;
  // The objective stress rates of each strain output with a stress (all but a t0 = 0
  // reference), by backward differences over the last outputs (strain/grid_stress_rates.h).
  std::optional<StressRateHistory> rate_history;
  if (strain_on) rate_history.emplace(output->grid_strain.rate_formula);
  // MPI runs: the same strain per compute grid (block), the sets by owner rank at t0
  // (Lagrangian) or now (Eulerian); no stress rates there, since a block's stress is neither
  // that of a fixed place nor of fixed material (docs/strain.md, "Compute grids").
  std::optional<io::ComputeGridStrainRecorder> block_strain_out;
  std::optional<StrainReference> block_reference;
  std::vector<Box> reference_blocks;
  std::optional<GridStrain> last_block_strain;
  auto evaluate_strain = [&](const RegularGrid& grid, const GridStress* stress) {
    const double t0 = output->grid_strain.reference_time;
    if (!strain_reference && t0 > 0.0 && sim.time() < t0 - 0.5 * scene.time_step) return;
    const ParticleStore& p = sim.whole_state();
    const std::vector<Box> blocks = sim.compute_grid_blocks();
    const std::vector<int> owner = sim.gather_owners_sorted_by_id();  // collective
    sim.on_root([&] {
      {
        const int count = static_cast<int>(blocks.size());
        if (!block_reference) {
          block_reference = make_strain_reference(p.id, p.x, owner, count, sim.time(), sim.step_count());
          reference_blocks = blocks;
        }
        GridStrain b =
            partition_strain(*block_reference, owner, {p.id, p.x, p.v}, sim.time(), sim.step_count(),
                             output->grid_strain.kernel, last_block_strain ? &*last_block_strain : nullptr);
        if (!block_strain_out) block_strain_out.emplace(output->folder);
        const bool lagrangian = output->grid_strain.kernel.set == StrainSet::lagrangian;
        if (lagrangian)
          block_strain_out->record(b, reference_blocks, block_reference->id, block_reference->cell);
        else
          block_strain_out->record(b, blocks, p.id, owner);
        last_block_strain = std::move(b);
      }
      if (!strain_reference)
        strain_reference = make_strain_reference(p.id, p.x, grid, sim.time(), sim.step_count());
      GridStrain g = grid_strain(*strain_reference, grid, {p.id, p.x, p.v}, sim.time(), sim.step_count(),
                                 output->grid_strain.kernel, r.final_strain ? &*r.final_strain : nullptr);
      if (stress) {
        const GridStressRates rates = rate_history->push((*stress)[output->grid_strain.rate_formula], g);
        strain_out->record(g, &rates);
      } else {
        strain_out->record(g);
      }
      r.final_strain = std::move(g);
    });
  };
  if (strain_on && output->grid_strain.reference_time <= 0.0)
    evaluate_strain(stress_grid(sim, output->grid_stress, scene.container), nullptr);
  auto evaluate_stress = [&] {
    r.final_grid = stress_grid(sim, output->grid_stress, scene.container);
    r.final_stress = sim.grid_stress(r.final_grid);
    sim.on_root([&] { stress_out->record(r.final_grid, *r.final_stress, sim.time(), sim.step_count()); });
    const ComputeGridStress blocks = sim.compute_grid_stress();
    sim.on_root([&] {
      if (!compute_grid_out) compute_grid_out.emplace(output->folder, output->grid_stress.formulas);
      compute_grid_out->record(blocks, sim.time(), sim.step_count());
    });
    if (strain_on) evaluate_strain(r.final_grid, &*r.final_stress);
  };

  // The collapse scenes: the gate (constrained) or the side walls (unconstrained) are
  // removed at their time (boundary/wall_release.h). The bed is not "at rest" before that,
  // nor in the first tenth of the time left after the last release: just after it the bed
  // is still as still as it was behind the walls.
  const std::vector<WallRelease> releases = wall_releases(scene.container);
  std::size_t next_release = 0;
  long rest_check_from = total / 10;
  const auto t0 = Clock::now();
  auto last_report = t0;
  const double pe0 = sim.initial_energy().potential;
  for (long s = 1; s <= total; ++s) {
    while (next_release < releases.size() && sim.time() >= releases[next_release].time) {
      for (const std::string& wall : releases[next_release].walls) sim.remove_wall(wall);
      ++next_release;
      rest_check_from = std::max(rest_check_from, s + (total - s) / 10);
    }
    const bool walls_pending = next_release < releases.size();
    if (stress_due(s)) sim.request_contacts();
    sim.step();
    if (stress_due(s)) evaluate_stress();
    const bool series_now = (s % series_every == 0) || s == total;
    if (series_now) {
      if (output) record_series();
      // Every rank takes the same decision: the energies are the same bits everywhere.
      if (control.rest_ratio > 0.0 && s > rest_check_from && !walls_pending &&
          sim.kinetic_to_released() < control.rest_ratio)
        r.stopped_at_rest = true;
    }
    if (output && ((s % snapshot_every == 0) || s == total || r.stopped_at_rest)) {
      if (!series_now) record_series();
      write_snapshot();
    }
    if (on_progress && sim.is_root()) {
      const auto now = Clock::now();
      if (std::chrono::duration<double>(now - last_report).count() >= 1.0 || s == total ||
          r.stopped_at_rest) {
        const double elapsed = std::chrono::duration<double>(now - t0).count();
        const double rate = s / std::max(elapsed, 1e-9);
        on_progress({s, total, rate, (total - s) / rate});
        last_report = now;
      }
    }
    if (r.stopped_at_rest) {
      if (stress_on && !stress_due(s) && !control.relax_at_end) {
        // One more step, recorded, so the final state has its stress.
        sim.request_contacts();
        sim.step();
        evaluate_stress();
        if (output) {
          record_series();
          write_snapshot();
        }
      }
      break;
    }
  }
  if (control.relax_at_end) {
    r.relaxation = relax_to_equilibrium(sim, control.relaxation);
    // One recorded step of the relaxed state for its stress, snapshot and series row.
    if (stress_on) sim.request_contacts();
    sim.step();
    if (stress_on) evaluate_stress();
    if (output) {
      record_series();
      write_snapshot();
    }
  }
  sim.check_finite();
  r.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  r.steps = sim.step_count();
  r.simulated_time = sim.time();
  const long n_particles = sim.particle_count();
  r.particle_steps_per_second =
      static_cast<double>(r.steps) * static_cast<double>(n_particles) / std::max(r.wall_seconds, 1e-9);
  r.energy = sim.energy();
  r.energy_balance_error = balance_error(sim.initial_energy(), r.energy);
  const double released = pe0 - r.energy.potential;
  r.kinetic_to_released = kinetic_to_released(sim.initial_energy(), r.energy);
  r.diagnostics = sim.diagnostics();
  r.load = sim.load();
  r.wall_forces = sim.wall_forces();
  for (const PlaneWall& w : sim.walls()) r.wall_names.push_back(w.name);
  const ParticleStore& all = sim.whole_state();
  sim.on_root([&] {
    r.bed = measure_bed(all, scene.container);
    for (std::size_t i = 0; i < all.size(); ++i) r.total_mass += all.mass(i);
    if (!recorder) return;
    recorder->flush();
    const auto n = static_cast<double>(n_particles);
    recorder->write_summary({
        {"particles", num(n)},
        {"mpi_ranks", num(sim.ranks())},
        {"summation", "\"" + to_string(sim.summation()) + "\""},
        {"effects", effects_json(output->effect_choices.empty() ? describe_effects(scene.effects)
                                                                 : output->effect_choices)},
        {"load_rebalances", num(static_cast<double>(r.load.rebalances))},
        {"load_owned_imbalance", num(r.load.owned_imbalance)},
        {"load_compute_imbalance", num(r.load.compute_imbalance)},
        {"load_communication_share", num(r.load.communication_share)},
        {"steps", num(static_cast<double>(r.steps))},
        {"simulated_time_s", num(r.simulated_time)},
        {"wall_time_s", num(r.wall_seconds)},
        {"particle_steps_per_second", num(r.particle_steps_per_second)},
        {"stopped_at_rest", r.stopped_at_rest ? "true" : "false"},
        {"kinetic_energy_J", num(r.energy.kinetic())},
        {"potential_energy_released_J", num(released)},
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
        {"relaxation_steps", num(r.relaxation ? static_cast<double>(r.relaxation->steps) : 0.0)},
        {"relaxation_force_residual", num(r.relaxation ? r.relaxation->max_force_residual : 0.0)},
        {"relaxation_torque_residual", num(r.relaxation ? r.relaxation->max_torque_residual : 0.0)},
    });
  });
  return r;
}

}  // namespace upgrain::dem
