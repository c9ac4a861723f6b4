#include "dem/parallel/parallel_engine.h"

#include "dem/parallel/exchange.h"
#include "dem/parallel/parallel_relaxation.h"
#include "dem/scene/fill.h"

namespace upgrain::dem {

ParallelEngine::ParallelEngine(ParallelSimulation& sim) : sim_(sim) {
  MPI_Comm_rank(sim_.comm(), &rank_);
  MPI_Comm_size(sim_.comm(), &ranks_);
}

void ParallelEngine::on_root(const std::function<void()>& work) {
  std::string error;
  if (rank_ == 0) {
    try {
      work();
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "unknown error";
    }
  }
  throw_if_any(sim_.comm(), error);
}

const ParticleStore& ParallelEngine::whole_state() {
  gathered_ = sim_.gather_sorted_by_id();
  return gathered_;
}

RegularGrid ParallelEngine::stress_grid(const io::GridStressOptions& options, const BoxContainer& box) {
  // The box of a moving grid needs the top (and extent) of the whole assembly; the root
  // finds it on the gathered state and every rank receives the same grid.
  RegularGrid g;
  const ParticleStore& all = whole_state();
  if (rank_ == 0) g = io::stress_grid(options, all, box);
  MPI_Bcast(g.n, 3, MPI_INT, 0, sim_.comm());
  MPI_Bcast(g.lo.data(), 3, MPI_DOUBLE, 0, sim_.comm());
  MPI_Bcast(g.hi.data(), 3, MPI_DOUBLE, 0, sim_.comm());
  return g;
}

RelaxationResult ParallelEngine::relax(const RelaxationOptions& options) {
  return relax_to_equilibrium(sim_, options);
}

EngineLoad ParallelEngine::load() const {
  const LoadImbalance b = sim_.load_imbalance();
  const ParallelTimings& t = sim_.timings();
  double share = t.total() > 0.0 ? t.communication() / t.total() : 0.0;
  MPI_Allreduce(MPI_IN_PLACE, &share, 1, MPI_DOUBLE, MPI_MAX, sim_.comm());
  EngineLoad l;
  l.ranks = ranks_;
  l.rebalances = sim_.diagnostics().rebalances;
  l.owned_imbalance = b.owned_ratio;
  l.compute_imbalance = b.compute_ratio;
  l.communication_share = share;
  return l;
}

DepositionResult run_parallel_deposition(const SceneConfig& scene, const RunControl& control,
                                         const std::optional<io::OutputOptions>& output,
                                         const std::function<void(const Progress&)>& on_progress,
                                         MPI_Comm comm, const ParallelOptions& options) {
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
  ParallelSimulation sim(scene, fill, comm, options);
  fill = ParticleStore{};
  ParallelEngine engine(sim);
  return run_deposition(engine, scene, control, output, on_progress);
}

}  // namespace upgrain::dem
