// Cost of the grid kinematics (docs/strain.md "Cost"): per evaluation of a grid,
// F and L per cell by best fit, by the tessellation, or both, with all measures and the
// increment (upscale::grid_strain, given the previous evaluation as in a run, so the reference
// tessellations of unchanged Lagrangian sets are reused), plus the objective stress rates
// of the cells (upscale::StressRateHistory). The share is that of a run that evaluates the kinematics every
// 1,000 steps of the same bed:
//   share = t_kinematics / (t_kinematics + t_1000_steps),
// with t_1000_steps measured once on the bed (best of 3) before the benchmarks run.
//
// The bed: 2,000 spheres (r = 1.5 mm, the default scene's) deposited for 0.3 s into a
// 4.5 cm square box with soft grains (E = 5e7 Pa, dt = 1e-5 s). The reference is that
// state; the current state is 1,000 steps later. The kinematics do not depend on the
// stiffness, the step cost barely does (same contacts per grain).
//
//   bench_grid_kinematics [--benchmark_repetitions=3 ...]
// Arguments of each case: cells per side along x and y (z has 4/3 as many), definition
// (0 best fit, 1 tessellation, 2 both).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "dem/engine/simulation.h"
#include "dem/io/grid_stress_output.h"
#include "dem/parallel/mpi_start.h"
#include "dem/scene/fill.h"
#include "upscale/strain/grid_strain.h"
#include "upscale/strain/grid_stress_rates.h"

using namespace upgrain::dem;
using namespace upgrain::upscale;

namespace {

struct Bed {
  std::unique_ptr<Simulation> sim;
  std::vector<GlobalId> id0;
  std::vector<Vec3> x0;
  double seconds_per_1000_steps = 0.0;
};

SceneConfig bed_scene() {
  SceneConfig s;
  s.particles.count = 2000;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = 0.045;
  s.fill.bottom_gap = 0.002;
  s.damping_ratio = 0.7;
  s.time_step = 1e-5;
  s.end_time = 1.0;
  s.effects.energy_tracking = false;
  return s;
}

Bed& bed() {
  static Bed b = [] {
    Bed out;
    const SceneConfig s = bed_scene();
    out.sim = std::make_unique<Simulation>(s, fill_container(s));
    out.sim->run(30000);  // 0.3 s: deposited
    const ParticleStore& p = out.sim->particles();
    out.id0 = p.id;
    out.x0 = p.x;
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      out.sim->run(1000);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    out.seconds_per_1000_steps = best;
    std::fprintf(stderr, "bed: %zu spheres, 1,000 steps take %.4f s (best of 3)\n", p.size(), best);
    return out;
  }();
  return b;
}

RegularGrid grid_of(const Simulation& sim, int cells_xy) {
  io::GridStressOptions o;
  o.cells[0] = o.cells[1] = cells_xy;
  o.cells[2] = std::max(1, cells_xy * 4 / 3);
  return io::stress_grid(o, sim.particles(), sim.scene().container);
}

void BM_GridKinematics(benchmark::State& state) {
  Bed& b = bed();
  const Simulation& sim = *b.sim;
  const RegularGrid grid = grid_of(sim, static_cast<int>(state.range(0)));
  const StrainReference ref = make_strain_reference(b.id0, b.x0, grid, 0.3, 30000);
  GridStrainOptions options;
  const auto which = state.range(1);
  options.definitions = {which != 1, which != 0};
  const ParticleStore& p = sim.particles();
  const std::vector<Mat3> stress(static_cast<std::size_t>(grid.num_cells()), -1e3 * Mat3::Identity());
  StressRateHistory history(StressFormula::bagi);
  // As in a run: each evaluation gets the previous one (F_prev for the increment, and the
  // reference tessellations kept while a cell's set is the same).
  std::optional<GridStrain> previous = grid_strain(ref, grid, {p.id, p.x, p.v}, {0.5, 0}, options);
  double t = 1.0;
  double seconds = 0.0;
  long evaluations = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    GridStrain g = grid_strain(ref, grid, {p.id, p.x, p.v}, {t, 0}, options, &*previous);
    const GridStressRates rates = history.push(stress, g);
    benchmark::DoNotOptimize(rates.fields[0].jaumann.data());
    previous = std::move(g);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++evaluations;
    t += 1.0;
  }
  const double per_grid = seconds / static_cast<double>(evaluations);
  state.counters["cells"] = grid.num_cells();
  state.counters["us_per_cell"] = 1e6 * per_grid / grid.num_cells();
  state.counters["share_at_1000_steps_pct"] = 100.0 * per_grid / (per_grid + b.seconds_per_1000_steps);
}

}  // namespace

BENCHMARK(BM_GridKinematics)
    ->ArgNames({"cells_xy", "definition"})
    ->ArgsProduct({{3, 6}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  upgrain::dem::MpiSession mpi(argc, argv);  // the engine runs on MPI_COMM_SELF
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
