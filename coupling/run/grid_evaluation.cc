#include "coupling/run/grid_evaluation.h"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "upscale/strain/cell_deformation.h"
#include "upscale/strain/periodic_kinematics.h"

namespace upgrain::coupling {

namespace {

// The grains as the strain takes them (docs/periodic.md, "Strain over a periodic cell"): in a
// periodic cell followed from their images at the reference time, with the mean flow's
// velocity added to the peculiar one; elsewhere as they are.
struct StrainGrains {
  upscale::PeriodicKinematics periodic;
  upscale::ParticleKinematics now;
};
StrainGrains strain_grains(const dem::Simulation& sim, const dem::ParticleStore& p,
                           const upscale::StrainReference& reference) {
  StrainGrains g;
  const dem::PeriodicCell& cell = sim.decomposition().cell();
  if (!cell.any()) {
    g.now = {p.id, p.x, p.v};
    return g;
  }
  // A reference without counters (written before they were kept): every grain from image 0.
  const std::vector<dem::ImageCount> zeros(reference.image.empty() ? reference.id.size() : 0, {0, 0, 0});
  g.periodic = upscale::periodic_kinematics(cell, sim.cell_velocity_gradient(), p.id, p.x, p.v, p.image,
                                            reference.id, reference.image.empty() ? zeros : reference.image);
  g.now = {p.id, g.periodic.x, g.periodic.v};
  return g;
}

// A periodic cell's reference keeps the counters at t0.
void keep_images(upscale::StrainReference& reference, const dem::Simulation& sim,
                 const dem::ParticleStore& p) {
  if (sim.decomposition().cell().any()) reference.image = p.image;
}

}  // namespace

GridEvaluation::GridEvaluation(dem::Simulation& sim, const OutputOptions& output,
                               const GridEvaluationState* resume)
    : output_(output), strain_on_(output.grid_strain.enabled) {
  sim.on_root([&] { stress_out_.emplace(output_.folder, output_.grid_stress.formulas); });
  if (strain_on_) {
    sim.on_root([&] {
      strain_out_.emplace(output_.folder);
      if (sim.scene().cell.any())
        cell_out_.emplace(std::filesystem::path(output_.folder) / "cell_deformation.csv",
                          upscale::cell_deformation_header());
    });
    rate_history_.emplace(output_.grid_strain.rate_formula);
  }
  if (resume) {
    sim.on_root([&] { restore(*resume, static_cast<int>(sim.compute_grid_blocks().size())); });
    return;
  }
  if (strain_on_ && output_.grid_strain.reference_time <= 0.0) evaluate_strain(sim, grid_now(sim), nullptr);
}

GridEvaluationState GridEvaluation::state() const {
  GridEvaluationState s;
  if (stress_out_) {
    s.stress_files = stress_out_->entries();
    s.stress_rows = stress_out_->csv_rows();
  }
  if (compute_grid_out_) s.compute_grid_rows = compute_grid_out_->csv_rows();
  if (strain_out_) {
    s.strain_files = strain_out_->entries();
    s.strain_rows = strain_out_->csv_rows();
  }
  s.reference = strain_reference_;
  s.previous = final_strain_;
  if (strain_on_) s.rates = rate_history_;
  s.block_reference = block_reference_;
  s.reference_blocks = reference_blocks_;
  s.previous_blocks = last_block_strain_;
  if (block_strain_out_) s.block_rows = block_strain_out_->csv_rows();
  if (cell_out_) s.cell_rows = cell_out_->rows();
  return s;
}

void GridEvaluation::restore(const GridEvaluationState& s, int blocks) {
  stress_out_->resume(s.stress_files, s.stress_rows);
  if (s.compute_grid_rows >= 0) {
    compute_grid_out_.emplace(output_.folder, output_.grid_stress.formulas);
    compute_grid_out_->resume(s.compute_grid_rows);
  }
  if (!strain_on_) return;
  strain_out_->resume(s.strain_files, s.strain_rows);
  if (cell_out_) cell_out_->resume(std::max(s.cell_rows, 0L));
  strain_reference_ = s.reference;
  final_strain_ = s.previous;
  if (s.rates) rate_history_ = s.rates;
  // The compute grids are the blocks of the rank count: on another one the strain per block
  // starts again from the next evaluation (docs/restart.md).
  if (s.block_reference && s.block_reference->cells == blocks) {
    block_reference_ = s.block_reference;
    reference_blocks_ = s.reference_blocks;
    last_block_strain_ = s.previous_blocks;
  }
  if (s.block_rows >= 0) {
    block_strain_out_.emplace(output_.folder);
    block_strain_out_->resume(s.block_rows);
  }
}

dem::RegularGrid GridEvaluation::grid_now(dem::Simulation& sim) const {
  dem::RegularGrid g;
  const dem::ParticleStore& all = sim.whole_state();
  if (sim.is_root()) g = dem::io::stress_grid(output_.grid_stress, all, sim.scene().container);
  MPI_Bcast(g.n, 3, MPI_INT, 0, sim.comm());
  MPI_Bcast(g.lo.data(), 3, MPI_DOUBLE, 0, sim.comm());
  MPI_Bcast(g.hi.data(), 3, MPI_DOUBLE, 0, sim.comm());
  return g;
}

void GridEvaluation::evaluate(dem::Simulation& sim) {
  final_grid_ = grid_now(sim);
  final_stress_ = sim.grid_stress(final_grid_);
  sim.on_root([&] { stress_out_->record(final_grid_, *final_stress_, sim.time(), sim.step_count()); });
  const dem::ComputeGridStress blocks = sim.compute_grid_stress();
  sim.on_root([&] {
    if (!compute_grid_out_) compute_grid_out_.emplace(output_.folder, output_.grid_stress.formulas);
    compute_grid_out_->record(blocks, sim.time(), sim.step_count());
  });
  if (strain_on_) evaluate_strain(sim, final_grid_, &*final_stress_);
}

void GridEvaluation::evaluate_block_strain(dem::Simulation& sim, const dem::ParticleStore& p,
                                           const std::vector<int>& owner) {
  const std::vector<dem::Box> blocks = sim.compute_grid_blocks();
  const int count = static_cast<int>(blocks.size());
  if (!block_reference_) {
    block_reference_ = upscale::make_strain_reference(p.id, p.x, owner, count, sim.time(), sim.step_count());
    keep_images(*block_reference_, sim, p);
    reference_blocks_ = blocks;
  }
  const StrainGrains grains = strain_grains(sim, p, *block_reference_);
  upscale::GridStrain b = upscale::partition_strain(
      *block_reference_, owner, grains.now, {sim.time(), sim.step_count()}, output_.grid_strain.kernel,
      last_block_strain_ ? &*last_block_strain_ : nullptr);
  if (!block_strain_out_) block_strain_out_.emplace(output_.folder);
  if (output_.grid_strain.kernel.set == upscale::StrainSet::lagrangian)
    block_strain_out_->record(b, reference_blocks_, block_reference_->id, block_reference_->cell);
  else
    block_strain_out_->record(b, blocks, p.id, owner);
  last_block_strain_ = std::move(b);
}

void GridEvaluation::evaluate_strain(dem::Simulation& sim, const dem::RegularGrid& grid,
                                     const dem::GridStress* stress) {
  const double t0 = output_.grid_strain.reference_time;
  if (!strain_reference_ && t0 > 0.0 && sim.time() < t0 - 0.5 * sim.time_step()) return;
  const dem::ParticleStore& p = sim.whole_state();
  const std::vector<int> owner = sim.gather_owners_sorted_by_id();  // collective
  sim.on_root([&] {
    evaluate_block_strain(sim, p, owner);
    if (!strain_reference_) {
      strain_reference_ = upscale::make_strain_reference(p.id, p.x, grid, sim.time(), sim.step_count());
      keep_images(*strain_reference_, sim, p);
      if (cell_out_) strain_reference_->cell_matrix = sim.cell_matrix();
    }
    const StrainGrains grains = strain_grains(sim, p, *strain_reference_);
    upscale::GridStrain g =
        upscale::grid_strain(*strain_reference_, grid, grains.now, {sim.time(), sim.step_count()},
                             output_.grid_strain.kernel, final_strain_ ? &*final_strain_ : nullptr, p.x);
    if (stress) {
      const upscale::GridStressRates rates =
          rate_history_->push((*stress)[output_.grid_strain.rate_formula], g);
      strain_out_->record(g, &rates);
    } else {
      strain_out_->record(g);
    }
    final_strain_ = std::move(g);
    if (cell_out_ && !strain_reference_->cell_matrix.isZero()) {
      const upscale::CellDeformation d = upscale::cell_deformation(
          strain_reference_->cell_matrix, sim.cell_matrix(), sim.decomposition().cell().periodic,
          strain_reference_->id, strain_reference_->x, p.id, grains.now.x);
      cell_out_->append(upscale::cell_deformation_row(sim.time(), sim.step_count(), d));
    }
  });
}

}  // namespace upgrain::coupling
