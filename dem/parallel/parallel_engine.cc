#include "dem/parallel/parallel_engine.h"

#include <algorithm>
#include <sstream>

#include "dem/parallel/exchange.h"
#include "dem/parallel/parallel_relaxation.h"
#include "dem/scene/fill.h"

namespace upgrain::dem {

ParallelEngine::ParallelEngine(ParallelSimulation& sim) : sim_(sim) {
  MPI_Comm_rank(sim_.comm(), &rank_);
  MPI_Comm_size(sim_.comm(), &ranks_);
}

void ParallelEngine::on_root(const std::function<void()>& work) { run_on_root(sim_.comm(), work); }

const ParticleStore& ParallelEngine::whole_state() {
  gathered_ = sim_.gather_sorted_by_id();
  // At every output: no particle lost or doubled, and the mass unchanged (summed in id
  // order, so exactly the same sum as at the first output).
  std::string error;
  if (rank_ == 0) {
    double mass = 0.0;
    for (std::size_t i = 0; i < gathered_.size(); ++i) mass += gathered_.mass(i);
    if (reference_mass_ < 0.0) reference_mass_ = mass;
    const long n = static_cast<long>(gathered_.size());
    const bool unique = std::adjacent_find(gathered_.id.begin(), gathered_.id.end()) == gathered_.id.end();
    if (n != sim_.diagnostics().particles || !unique || mass != reference_mass_) {
      std::ostringstream m;
      m.precision(17);
      m << "parallel run: the gathered state at step " << sim_.step_count() << " has " << n << " particles"
        << (unique ? "" : " with repeated ids") << " of mass " << mass << " kg; expected "
        << sim_.diagnostics().particles << " particles of mass " << reference_mass_ << " kg";
      error = m.str();
    }
  }
  throw_if_any(sim_.comm(), error);
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
