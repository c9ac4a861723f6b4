// The load balance of ParallelSimulation (docs/parallel.md, "Load balance"): at a
// neighbour-list rebuild, before migration, every rank bins the cost of its owned particles
// along each cut axis; one integer MPI_Allreduce sums the histograms (exact, so the same
// numbers on every rank whatever the reduction order), and every rank places the planes at
// the quantiles of the same histogram (quantile_cuts, clamp_cuts: load_balance.h). The
// planes are therefore bit for bit the same everywhere; they never enter the physics.
#include <algorithm>
#include <chrono>

#include "dem/parallel/load_balance.h"
#include "dem/parallel/parallel_simulation.h"

namespace upgrain::dem {

long ParallelSimulation::owned_cost(int i) const {
  if (balance_.cost == BalanceCost::particles) return 1;
  // The particle and its neighbour-list row (lists of the last build: the owned particles
  // have not changed since).
  if (lists_.row_start.size() != static_cast<std::size_t>(n_owned_) + 1) return 1;
  return 1 + lists_.row_start[i + 1] - lists_.row_start[i];
}

bool ParallelSimulation::rebalance_if_due() {
  if (balance_.interval <= 0 || step_ < balance_.next_step) return false;
  balance_.next_step = step_ + balance_.interval;
  Decomposition& dec = *decomp_;
  const std::array<int, 3>& blocks = dec.blocks();
  const Box& box = dec.box();
  const std::size_t n = 3 * static_cast<std::size_t>(kBalanceBins) + 1;
  balance_.histogram.assign(n, 0);
  balance_.reduced.assign(n, 0);
  long* h = balance_.histogram.data();
  long mine = 0;
  for (int i = 0; i < n_owned_; ++i) {
    const long w = owned_cost(i);
    mine += w;
    for (int d = 0; d < 3; ++d) {
      if (blocks[d] < 2) continue;
      h[d * kBalanceBins + balance_bin(p_.x[i][d], box.lo[d], box.hi[d], kBalanceBins)] += w;
    }
  }
  h[n - 1] = mine;
  long max_cost = 0;
  const std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  MPI_Allreduce(h, balance_.reduced.data(), static_cast<int>(n), MPI_LONG, MPI_SUM, comm_);
  MPI_Allreduce(&mine, &max_cost, 1, MPI_LONG, MPI_MAX, comm_);
  timings_.rebuild_messages += seconds_since(t);
  balance_.before = imbalance_ratio(max_cost, balance_.reduced[n - 1], dec.size());
  for (int d = 0; d < 3; ++d) {
    if (blocks[d] < 2) continue;
    std::vector<double> cuts = quantile_cuts(balance_.reduced.data() + d * kBalanceBins, kBalanceBins,
                                             box.lo[d], box.hi[d], blocks[d]);
    clamp_cuts(cuts, box.lo[d], box.hi[d], dec.min_block());
    dec.set_cuts(d, cuts);
  }
  ++balance_.count;
  balance_.last_step = step_;
  balance_.measure_after = true;
  return true;
}

void ParallelSimulation::measure_balance_after() {
  balance_.measure_after = false;
  long mine = 0;
  for (int i = 0; i < n_owned_; ++i) mine += owned_cost(i);
  long max_cost = 0, total = 0;
  const std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  MPI_Allreduce(&mine, &max_cost, 1, MPI_LONG, MPI_MAX, comm_);
  MPI_Allreduce(&mine, &total, 1, MPI_LONG, MPI_SUM, comm_);
  timings_.rebuild_messages += seconds_since(t);
  balance_.after = imbalance_ratio(max_cost, total, decomp_->size());
}

}  // namespace upgrain::dem
