#include "coupling/run/run_files.h"

namespace upgrain::coupling {

RunFiles::RunFiles(dem::Simulation& sim, const std::optional<OutputOptions>& output) : output_(output) {
  if (output_) sim.on_root([&] { recorder_.emplace(output_->folder); });
  if (output_ && output_->force_network) network_.emplace(sim.comm(), output_->folder);
}

void RunFiles::record_series(dem::Simulation& sim) {
  if (!output_) return;
  const dem::EnergyBalance e = sim.energy();
  const dem::StepDiagnostics d = sim.diagnostics();
  const std::vector<dem::Vec3> forces = sim.wall_forces();
  sim.on_root([&] {
    recorder_->record_series(sim.time(), sim.step_count(), e, dem::balance_error(sim.initial_energy(), e), d);
    std::vector<bool> present(sim.walls().size());
    for (std::size_t w = 0; w < present.size(); ++w) present[w] = !sim.wall_removed(w);
    recorder_->record_walls(sim.time(), sim.step_count(), sim.walls(), present, forces);
  });
}

void RunFiles::write_snapshot(dem::Simulation& sim) {
  if (!output_) return;
  sim.check_finite();
  const std::vector<dem::Vec3> forces = sim.wall_forces();
  // Every rank writes its rows of the state sorted by id into the one file (no rank holds the
  // whole: docs/parallel.md, "Output"); rank 0 then lists it. A periodic cell's snapshots carry
  // the image counters (docs/periodic.md).
  dem::IdSlice slice = sim.whole_state_slice();
  const std::filesystem::path name = dem::io::RunRecorder::snapshot_name(sim.step_count());
  dem::io::write_snapshot(sim.comm(), output_->folder / name, slice.grains,
                          {slice.first_row, slice.total_rows, sim.decomposition().cell().any(), slice.shapes},
                          sim.walls(), forces, sim.time(), sim.step_count());
  sim.on_root([&] {
    recorder_->add_snapshot({name.string(), sim.time(), sim.step_count(), slice.total_rows, slice.shapes});
  });
  if (!network_ || !sim.contacts_recorded()) return;
  // Every contact once, each rank those of its rows' grains, with the partners from other rows
  // that they touch: the same data sets on any rank count with the deterministic summation.
  const std::vector<dem::ContactRecord> contacts = sim.contacts_of_rows(slice);
  network_->write({slice.grains, slice.first_row, slice.rows}, slice.total_rows, sim.walls(), contacts,
                  sim.decomposition().cell(), sim.time(), sim.step_count());
}

dem::io::RunRecorder::State RunFiles::state() {
  if (!recorder_) return {};
  recorder_->flush();
  return recorder_->state();
}

void RunFiles::resume(dem::Simulation& sim, const dem::io::RunRecorder::State& s) {
  if (output_)
    sim.on_root([&] {
      recorder_->resume(s);
      if (network_) network_->resume();
    });
}

void RunFiles::write_summary(const dem::Simulation& sim, const RunResult& r) {
  if (!output_) return;
  sim.on_root([&] {
    recorder_->flush();
    recorder_->write_summary(summary_entries(sim, r,
                                             output_->effect_choices.empty()
                                                 ? dem::describe_effects(sim.scene().effects)
                                                 : output_->effect_choices));
  });
}

}  // namespace upgrain::coupling
