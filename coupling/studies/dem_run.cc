#include "coupling/studies/dem_run.h"

#include "coupling/run/scene_run.h"

#include <algorithm>
#include <cmath>

#include "dem/parallel/exchange.h"

namespace upgrain::coupling {

dem::EngineOptions engine_options(const SceneInput& in) {
  dem::EngineOptions o;
  o.summation = in.parallel.summation;
  dem::DomainOptions& d = o;
  if (in.parallel.blocks[0] > 0) d.blocks = in.parallel.blocks;
  if (in.parallel.balance_interval > 0.0) {
    d.balance_interval =
        std::max(1L, static_cast<long>(std::llround(in.parallel.balance_interval / in.scene.time_step)));
    d.balance_at_start = true;
  } else {
    d.balance_interval = 0;
    d.balance_at_start = false;
  }
  d.balance_cost = in.parallel.balance_by_pairs ? dem::BalanceCost::pair_slots : dem::BalanceCost::particles;
  return o;
}

RunResult run_dem(const SceneInput& in, MPI_Comm comm,
                  const std::function<void(const Progress&)>& on_progress) {
  if (in.restarting) {
    static const Checkpoint none;
    return resume_scene(in.scene, in.resume ? *in.resume : none, in.control, in.output, on_progress, comm,
                        engine_options(in));
  }
  return run_scene(in.scene, in.control, in.output, on_progress, comm, engine_options(in));
}

void on_rank0(MPI_Comm comm, const std::function<void()>& work) { dem::run_on_root(comm, work); }

}  // namespace upgrain::coupling
