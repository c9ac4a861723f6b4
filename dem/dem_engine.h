#pragma once
// What a whole run (dem/deposition.h) needs of a DEM engine, so that one run loop drives
// the serial Simulation and the MPI ParallelSimulation alike. Called a few times per step
// at most (never per contact), so a virtual interface costs nothing measurable.
//
// Every method is collective: every rank calls it at the same point of the run and
// receives the same answer, except whole_state(), which holds the state on the root only.
// Output is written by the root inside on_root(), which turns an error there into the same
// error on every rank, so no rank is left waiting in a later message.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/core/particle_store.h"
#include "dem/energy.h"
#include "dem/io/run_recorder.h"
#include "dem/parallel/parallel_stress.h"
#include "dem/relaxation.h"
#include "dem/simulation.h"
#include "dem/stress/grid_stress.h"

namespace upgrain::dem {

// How the work was shared among the ranks (for the log and summary.json).
struct EngineLoad {
  int ranks = 1;
  long rebalances = 0;               // moves of the block planes (docs/parallel.md, "Load balance")
  double owned_imbalance = 1.0;      // max/mean of the particles owned per rank, now
  double compute_imbalance = 1.0;    // max/mean of the compute seconds per rank
  double communication_share = 0.0;  // largest share of a rank's step time spent in messages
};

class DemEngine {
 public:
  virtual ~DemEngine() = default;

  [[nodiscard]] virtual int ranks() const = 0;
  [[nodiscard]] virtual bool is_root() const = 0;
  // Runs `work` on the root; an exception there is thrown on every rank.
  virtual void on_root(const std::function<void()>& work) = 0;

  virtual void step() = 0;
  // The next step records its contacts, for grid_stress() after it.
  virtual void request_contacts() = 0;
  [[nodiscard]] virtual long step_count() const = 0;
  [[nodiscard]] virtual double time() const = 0;
  [[nodiscard]] virtual long particle_count() const = 0;
  virtual void remove_wall(const std::string& name) = 0;
  [[nodiscard]] virtual const std::vector<PlaneWall>& walls() const = 0;
  [[nodiscard]] virtual Vec3 gravity() const = 0;
  [[nodiscard]] virtual bool integrates_rotation() const = 0;

  [[nodiscard]] virtual EnergyBalance energy() const = 0;
  [[nodiscard]] virtual const EnergyBalance& initial_energy() const = 0;
  [[nodiscard]] virtual StepDiagnostics diagnostics() const = 0;
  [[nodiscard]] virtual std::vector<Vec3> wall_forces() const = 0;
  virtual void check_finite() const = 0;

  // The whole state on the root (any particle order; the snapshot writer sorts by id), an
  // empty store on the other ranks. The reference is valid until the next call or step.
  [[nodiscard]] virtual const ParticleStore& whole_state() = 0;
  // The grid of an evaluation (io::stress_grid of the whole state), the same on every rank.
  [[nodiscard]] virtual RegularGrid stress_grid(const io::GridStressOptions& options,
                                                const BoxContainer& box) = 0;
  // After a step that recorded contacts: the stress of `grid`, on every rank.
  [[nodiscard]] virtual GridStress grid_stress(const RegularGrid& grid) = 0;
  // After the same step: the stress per compute grid (MPI block), on every rank; none for
  // an engine without blocks.
  [[nodiscard]] virtual std::optional<ComputeGridStress> compute_grid_stress() { return std::nullopt; }
  // The compute grids (MPI blocks) now: the blocks, clipped to the decomposition box, on every
  // rank, and the block (owner rank) of each particle of the last whole_state(), in its order,
  // on the root. None for an engine without blocks.
  struct ComputeGrids {
    std::vector<Box> block;
    std::vector<int> owner;
  };
  [[nodiscard]] virtual std::optional<ComputeGrids> compute_grids() { return std::nullopt; }
  virtual RelaxationResult relax(const RelaxationOptions& options) = 0;
  [[nodiscard]] virtual EngineLoad load() const = 0;

  // Shared by both engines (energy.h): the balance error and the kinetic-to-released ratio.
  [[nodiscard]] double energy_balance_error() const { return balance_error(initial_energy(), energy()); }
  [[nodiscard]] double kinetic_to_released() const {
    return dem::kinetic_to_released(initial_energy(), energy());
  }
};

// The serial engine: a Simulation on one process.
class SerialEngine final : public DemEngine {
 public:
  explicit SerialEngine(Simulation& sim) : sim_(sim) {}
  [[nodiscard]] int ranks() const override { return 1; }
  [[nodiscard]] bool is_root() const override { return true; }
  void on_root(const std::function<void()>& work) override { work(); }
  void step() override { sim_.step(); }
  void request_contacts() override { sim_.request_contacts(); }
  [[nodiscard]] long step_count() const override { return sim_.step_count(); }
  [[nodiscard]] double time() const override { return sim_.time(); }
  [[nodiscard]] long particle_count() const override { return static_cast<long>(sim_.particles().size()); }
  void remove_wall(const std::string& name) override { sim_.remove_wall(name); }
  [[nodiscard]] const std::vector<PlaneWall>& walls() const override { return sim_.walls(); }
  [[nodiscard]] Vec3 gravity() const override { return sim_.gravity(); }
  [[nodiscard]] bool integrates_rotation() const override { return sim_.integrates_rotation(); }
  [[nodiscard]] EnergyBalance energy() const override { return sim_.energy(); }
  [[nodiscard]] const EnergyBalance& initial_energy() const override { return sim_.initial_energy(); }
  [[nodiscard]] StepDiagnostics diagnostics() const override { return sim_.diagnostics(); }
  [[nodiscard]] std::vector<Vec3> wall_forces() const override { return sim_.wall_forces(); }
  void check_finite() const override { sim_.check_finite(); }
  [[nodiscard]] const ParticleStore& whole_state() override { return sim_.particles(); }
  [[nodiscard]] RegularGrid stress_grid(const io::GridStressOptions& options,
                                        const BoxContainer& box) override {
    return io::stress_grid(options, sim_.particles(), box);
  }
  [[nodiscard]] GridStress grid_stress(const RegularGrid& grid) override {
    return dem::grid_stress(sim_.particles(), sim_.contacts(), grid,
                            {sim_.gravity(), sim_.integrates_rotation()});
  }
  RelaxationResult relax(const RelaxationOptions& options) override {
    return relax_to_equilibrium(sim_, options);
  }
  [[nodiscard]] EngineLoad load() const override { return {}; }

 private:
  Simulation& sim_;
};

}  // namespace upgrain::dem
