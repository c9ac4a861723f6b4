#pragma once
// The MPI engine behind the run loop (dem/dem_engine.h): a ParallelSimulation whose
// whole state is gathered on rank 0, sorted by global id, when output needs it, and whose
// grid stress is the parallel one (bitwise the same on any rank count).
#include <mpi.h>

#include <functional>
#include <optional>

#include "dem/dem_engine.h"
#include "dem/deposition.h"
#include "dem/parallel/parallel_simulation.h"

namespace upgrain::dem {

class ParallelEngine final : public DemEngine {
 public:
  explicit ParallelEngine(ParallelSimulation& sim);
  [[nodiscard]] int ranks() const override { return ranks_; }
  [[nodiscard]] bool is_root() const override { return rank_ == 0; }
  void on_root(const std::function<void()>& work) override;
  void step() override { sim_.step(); }
  void request_contacts() override { sim_.request_contacts(); }
  [[nodiscard]] long step_count() const override { return sim_.step_count(); }
  [[nodiscard]] double time() const override { return sim_.time(); }
  [[nodiscard]] long particle_count() const override { return sim_.diagnostics().particles; }
  void remove_wall(const std::string& name) override { sim_.remove_wall(name); }
  [[nodiscard]] const std::vector<PlaneWall>& walls() const override { return sim_.walls(); }
  [[nodiscard]] Vec3 gravity() const override { return sim_.gravity(); }
  [[nodiscard]] bool integrates_rotation() const override { return sim_.integrates_rotation(); }
  [[nodiscard]] EnergyBalance energy() const override { return sim_.energy(); }
  [[nodiscard]] const EnergyBalance& initial_energy() const override { return sim_.initial_energy(); }
  [[nodiscard]] StepDiagnostics diagnostics() const override { return sim_.step_diagnostics(); }
  [[nodiscard]] std::vector<Vec3> wall_forces() const override { return sim_.wall_forces(); }
  void check_finite() const override { sim_.check_finite(); }
  [[nodiscard]] const ParticleStore& whole_state() override;
  [[nodiscard]] RegularGrid stress_grid(const io::GridStressOptions& options,
                                        const BoxContainer& box) override;
  [[nodiscard]] GridStress grid_stress(const RegularGrid& grid) override { return sim_.grid_stress(grid); }
  [[nodiscard]] std::optional<ComputeGridStress> compute_grid_stress() override {
    return sim_.compute_grid_stress();
  }
  [[nodiscard]] std::optional<ComputeGrids> compute_grids() override {
    return ComputeGrids{sim_.compute_grid_blocks(), sim_.gather_owners_sorted_by_id()};
  }
  RelaxationResult relax(const RelaxationOptions& options) override;
  [[nodiscard]] EngineLoad load() const override;

 private:
  ParallelSimulation& sim_;
  int rank_ = 0;
  int ranks_ = 1;
  ParticleStore gathered_;
  double reference_mass_ = -1.0;  // of the first gathered state (rank 0)
};

// The whole run (run_deposition) on the MPI engine, collective over `comm`: rank 0 fills
// the container, every rank keeps the grains of its block. The result is complete on
// rank 0 (dem/deposition.h); the output files hold the same bytes on any rank count
// (docs/parallel.md, "Runs from the driver").
DepositionResult run_parallel_deposition(const SceneConfig& scene, const RunControl& control,
                                         const std::optional<io::OutputOptions>& output,
                                         const std::function<void(const Progress&)>& on_progress,
                                         MPI_Comm comm, const ParallelOptions& options = {});

}  // namespace upgrain::dem
