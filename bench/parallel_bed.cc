// MPI benchmark: the settled dense bed of bench_dense_bed, stepped by the engine on the ranks
// it is started with.
//   mpiexec -n K bench_parallel_bed bed.data [steps] [--summation deterministic|fast]
//           [--blocks PXxPYxPZ] [--wedge] [--balance STEPS] [--balance-cost particles|pair_slots]
// (blocks: default chosen by the decomposition rule, docs/parallel.md). --wedge keeps only
// the grains below the plane from the top of the bed at x = 0 to the floor at x = lx (a heap
// against one wall: a strongly non-uniform bed, 1/4 of the grains in the right half);
// --balance moves the planes (EngineOptions::balance_interval, at construction and at
// rebuilds; docs/parallel.md, "Load balance"), and the line then also reports the owned
// imbalance before the timed run, the rebalances and the last before/after figures.
// Rank 0 prints one line of `key value` pairs: particles, steps, wall seconds, particle-
// steps/s, the share of time in communication (per-step reduction, ghost refresh, messages
// of rebuilds; mean over ranks of StepTimings), the imbalance (max/mean of owned
// particles, pair slots and compute seconds), neighbour rebuilds, and a hash of the final
// state sorted by id (with deterministic summation bitwise rank-independent, so equal for every
// K), with the summation (docs/architecture.md). One `rank` line per rank follows on stderr.
// bench/parallel_scaling.py runs both summations on K = 1 and 2 and compares.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "bench/dense_bed_scene.h"
#include "dem/engine/simulation.h"
#include "dem/parallel/mpi_start.h"
#include "dem/parallel/records.h"

using namespace upgrain::dem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// FNV-1a over the bytes of x, v and omega, in id order.
std::uint64_t state_hash(const ParticleStore& p) {
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&h](const Vec3& a) {
    unsigned char bytes[3 * sizeof(double)];
    for (int d = 0; d < 3; ++d) {
      const double c = a[d];
      std::memcpy(bytes + d * sizeof(double), &c, sizeof(double));
    }
    for (unsigned char b : bytes) {
      h ^= b;
      h *= 1099511628211ull;
    }
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    add(p.x[i]);
    add(p.v[i]);
    add(p.omega[i]);
  }
  return h;
}

// The grains below the plane z = z_top (1 - x / lx), renumbered from 0.
ParticleStore wedge_of(const ParticleStore& p, double lx) {
  double z_top = 0.0;
  for (const Vec3& x : p.x) z_top = std::max(z_top, x[2]);
  ParticleStore out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.x[i][2] > z_top * (1.0 - p.x[i][0] / lx)) continue;
    StateRecord r = pack_state(p, i);
    r.gid = static_cast<GlobalId>(out.size());
    append_state(out, r);
  }
  return out;
}

int run(const std::string& path, long steps, bool wedge, const EngineOptions& options) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  // Every rank reads the scene; rank 0's particles are the bed (Simulation
  // broadcasts them).
  std::optional<upgrain::bench::Bed> bed = upgrain::bench::read_bed(path);
  int ok = bed ? 1 : 0, all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (!all_ok) {
    if (rank == 0) std::fprintf(stderr, "cannot open %s\n", path.c_str());
    return 1;
  }
  if (rank != 0) bed->particles = ParticleStore{};
  if (wedge && rank == 0) bed->particles = wedge_of(bed->particles, bed->scene.container.lx);
  long n_global = static_cast<long>(bed->particles.size());
  MPI_Bcast(&n_global, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  const long n = n_global;

  const auto t_setup = std::chrono::steady_clock::now();
  Simulation sim(bed->scene, bed->particles, MPI_COMM_WORLD, options);
  const double setup_seconds = seconds_since(t_setup);
  const long rebuilds_before = sim.rank_diagnostics().rebuilds;
  const LoadImbalance at_start = sim.load_imbalance();
  MPI_Barrier(MPI_COMM_WORLD);
  const auto t0 = std::chrono::steady_clock::now();
  sim.run(steps);
  MPI_Barrier(MPI_COMM_WORLD);
  const double wall = seconds_since(t0);

  const RankDiagnostics diag = sim.rank_diagnostics();
  const LoadImbalance imbalance = sim.load_imbalance();
  const StepTimings& t = sim.timings();
  // Per rank: owned, ghosts, pair slots, then the timing parts.
  constexpr int kFields = 10;
  const double mine[kFields] = {static_cast<double>(diag.owned),
                                static_cast<double>(diag.ghosts),
                                static_cast<double>(diag.pair_slots),
                                t.integrate,
                                t.forces,
                                t.reduction,
                                t.ghost_refresh,
                                t.rebuild,
                                t.rebuild_messages,
                                t.total()};
  std::vector<double> every(rank == 0 ? kFields * size : 0);
  MPI_Gather(mine, kFields, MPI_DOUBLE, every.data(), kFields, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  const ParticleStore final_state = sim.gather_sorted_by_id();
  if (rank != 0) return 0;

  double share = 0.0, share_reduction = 0.0, share_refresh = 0.0, share_rebuild = 0.0;
  double ghosts_max = 0.0;
  for (int r = 0; r < size; ++r) {
    const double* f = every.data() + kFields * r;
    const double total = f[9] > 0.0 ? f[9] : 1.0;
    share += (f[5] + f[6] + f[8]) / total / size;
    share_reduction += f[5] / total / size;
    share_refresh += f[6] / total / size;
    share_rebuild += f[8] / total / size;
    ghosts_max = std::max(ghosts_max, f[1]);
    std::fprintf(
        stderr,
        "rank %d owned %.0f ghosts %.0f pair_slots %.0f integrate_s %.4f forces_s %.4f reduction_s %.4f "
        "ghost_refresh_s %.4f rebuild_s %.4f rebuild_messages_s %.4f total_s %.4f\n",
        r, f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8], f[9]);
  }
  const std::array<int, 3>& b = sim.decomposition().blocks();
  std::printf(
      "parallel summation %s ranks %d blocks %dx%dx%d particles %ld steps %ld seconds %.4f "
      "particle_steps_per_second %.4e "
      "comm_share %.4f reduction_share %.4f ghost_refresh_share %.4f rebuild_messages_share %.4f "
      "owned_imbalance %.4f pairs_imbalance %.4f compute_imbalance %.4f rebuilds %ld ghosts_max %.0f "
      "state_hash %016llx",
      to_string(options.summation).c_str(), size, b[0], b[1], b[2], n, steps, wall,
      static_cast<double>(n) * steps / wall, share, share_reduction, share_refresh, share_rebuild,
      imbalance.owned_ratio, imbalance.pairs_ratio, imbalance.compute_ratio, diag.rebuilds - rebuilds_before,
      ghosts_max, static_cast<unsigned long long>(state_hash(final_state)));
  if (options.balance_interval > 0 || wedge)
    std::printf(
        " wedge %d balance_interval %ld owned_imbalance_start %.4f setup_seconds %.4f rebalances %ld "
        "last_rebalance_before %.4f last_rebalance_after %.4f",
        wedge ? 1 : 0, options.balance_interval, at_start.owned_ratio, setup_seconds, diag.rebalances,
        diag.imbalance_before, diag.imbalance_after);
  std::printf("\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  upgrain::dem::prefer_isolated_singleton();
  MPI_Init(&argc, &argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  bool usage = false;
  bool wedge = false;
  EngineOptions options;
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--summation" && i + 1 < args.size()) {
      const std::string m = args[++i];
      usage = usage || (m != "deterministic" && m != "fast");
      options.summation = m == "fast" ? Summation::fast : Summation::deterministic;
    } else if (args[i] == "--wedge") {
      wedge = true;
    } else if (args[i] == "--balance" && i + 1 < args.size()) {
      options.balance_interval = std::atol(args[++i].c_str());
      usage = usage || options.balance_interval <= 0;
    } else if (args[i] == "--balance-cost" && i + 1 < args.size()) {
      const std::string c = args[++i];
      usage = usage || (c != "particles" && c != "pair_slots");
      options.balance_cost = c == "pair_slots" ? BalanceCost::pair_slots : BalanceCost::particles;
    } else if (args[i] == "--blocks" && i + 1 < args.size()) {
      std::array<int, 3>& b = options.blocks;
      usage = usage || std::sscanf(args[++i].c_str(), "%dx%dx%d", &b[0], &b[1], &b[2]) != 3;
    } else {
      positional.push_back(args[i]);
    }
  }
  int code = 2;
  if (!usage && (positional.size() == 1 || positional.size() == 2)) {
    try {
      code =
          run(positional[0], positional.size() > 1 ? std::atol(positional[1].c_str()) : 1000, wedge, options);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_parallel_bed: %s\n", e.what());
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
  } else {
    std::fprintf(stderr,
                 "usage: mpiexec -n K bench_parallel_bed bed.data [steps] [--summation deterministic|fast] "
                 "[--blocks PXxPYxPZ] [--wedge] "
                 "[--balance STEPS] [--balance-cost particles|pair_slots]\n");
  }
  MPI_Finalize();
  return code;
}
