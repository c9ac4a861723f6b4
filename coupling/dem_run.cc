#include "coupling/dem_run.h"

#include <algorithm>
#include <cmath>

#include "dem/parallel/exchange.h"
#include "dem/parallel/parallel_engine.h"

namespace upgrain::coupling {

EngineChoice choose_engine(const SceneInput& in, int ranks) {
  switch (in.parallel.engine) {
    case DemEngineChoice::mpi:
      return {true, "Parallel/DEM engine = mpi"};
    case DemEngineChoice::serial:
      return {false, "Parallel/DEM engine = serial"};
    case DemEngineChoice::automatic:
      break;
  }
  if (ranks == 1) return {false, "one rank"};
  if (in.scene.effects.rolling_resistance)
    return {false, "Effects/rolling resistance, which the MPI engine does not have yet"};
  return {true, std::to_string(ranks) + " ranks"};
}

dem::DepositionResult run_dem(const SceneInput& in, MPI_Comm comm,
                              const std::function<void(const dem::Progress&)>& on_progress) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  dem::DepositionResult r;
  if (choose_engine(in, ranks).mpi) {
    dem::ParallelOptions o;
    if (in.parallel.blocks[0] > 0) o.blocks = in.parallel.blocks;
    if (in.parallel.balance_interval > 0.0) {
      o.balance_interval =
          std::max(1L, static_cast<long>(std::llround(in.parallel.balance_interval / in.scene.time_step)));
      o.balance_at_start = true;
    } else {
      o.balance_interval = 0;
      o.balance_at_start = false;
    }
    o.balance_cost =
        in.parallel.balance_by_pairs ? dem::BalanceCost::pair_slots : dem::BalanceCost::particles;
    return dem::run_parallel_deposition(in.scene, in.control, in.output, on_progress, comm, o);
  }
  on_rank0(comm, [&] { r = dem::run_deposition(in.scene, in.control, in.output, on_progress); });
  return r;
}

void on_rank0(MPI_Comm comm, const std::function<void()>& work) { dem::run_on_root(comm, work); }

}  // namespace upgrain::coupling
