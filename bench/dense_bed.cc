// Dense-bed benchmark: a settled bed of monodisperse spheres, 2,000 steps from
// the settled state. Two modes, so that Upgrain and LIGGGHTS start from the same file:
//   bench_dense_bed settle N bed.data   deposit N spheres, relax them with the benchmark
//                                        material, write a LAMMPS/LIGGGHTS data file
//   bench_dense_bed run bed.data [steps [summation]]
//                                        time `steps` steps (default 2000) from the file with
//                                        the given summation (deterministic, the default, or
//                                        fast) and print particle-steps/s, contacts per
//                                        particle and peak memory per particle; under callgrind
//                                        the timed steps are a profile file of their own (`.1`)
//   bench_dense_bed stress bed.data OUT [steps [evaluations]]
//                                        cost of grid stress per contact and its share of a
//                                        run that evaluates it every 1,000 steps
// Benchmark scene: r = 1.5 mm, 2,650 kg/m^3, E = 29 GPa, nu = 0.25, mu = 0.5 (particles
// and walls), zeta = 0.5, dt = 1e-6 s, gravity on.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include <memory>

#include "bench/callgrind_marks.h"
#include "bench/dense_bed_scene.h"
#include "dem/engine/simulation.h"
#include "dem/io/grid_stress_output.h"
#include "dem/parallel/mpi_start.h"
#include "dem/scene/fill.h"

using namespace upgrain::dem;

namespace {

using upgrain::bench::benchmark_scene;

double peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0;
}

// Resident memory now, from /proc/self/statm (pages).
double current_rss_bytes() {
  std::ifstream statm("/proc/self/statm");
  double size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

int settle(long n, const std::string& path) {
  const double r = 1.5e-3;
  // A square box whose bed is about as high as it is wide at solid fraction 0.6.
  const double side = std::cbrt(n * 4.0 / 3.0 * std::numbers::pi * r * r * r / 0.6);
  SceneConfig s = benchmark_scene(side);
  s.particles.count = n;
  s.fill.bottom_gap = 0.002;
  s.fill.position_jitter = 0.5;
  s.effects.energy_tracking = true;
  // Deposit with a soft material (large stable step), then relax with the real one.
  s.particles.material.youngs_modulus = 1e8;
  s.time_step = 8e-6;
  s.end_time = 1.0;
  constexpr double kRestRatio = 1e-5;
  const auto t0 = std::chrono::steady_clock::now();
  std::fprintf(stderr, "settle: %ld spheres in a %.4f m square box (soft deposition)\n", n, side);
  Simulation soft(s, fill_container(s));
  for (long k = 1; k * s.time_step <= s.end_time; ++k) {
    soft.step();
    if (k % 2000 == 0 && k * s.time_step > 0.1 && soft.kinetic_to_released() < kRestRatio) break;
  }
  std::fprintf(stderr, "settle: soft bed at rest after %.3f s; relaxing with E = 29 GPa\n", soft.time());
  // Stiffen in steps of about 4x, relaxing at each, so that the overlaps of the soft bed
  // do not turn into a burst of elastic energy that lifts the bed.
  ParticleStore p = soft.particles();
  const double moduli[] = {4e8, 1.6e9, 6.4e9, 29e9};
  for (double e : moduli) {
    SceneConfig stage = benchmark_scene(side);
    stage.particles.material.youngs_modulus = e;
    stage.time_step = std::min(8e-6 * std::sqrt(1e8 / e), 1e-6 * std::sqrt(29e9 / e));
    stage.damping_ratio = 1.0;
    for (auto& v : p.v) v.setZero();
    for (auto& w : p.omega) w.setZero();
    Simulation relax(stage, p);
    // Grains lifted by the stiffening fall back within about 10 ms: relax 20 ms per stage,
    // 40 ms at the final modulus.
    relax.run(std::lround((e < 29e9 ? 0.02 : 0.04) / stage.time_step));
    p = relax.particles();
    std::fprintf(stderr, "settle: relaxed at E = %.2g Pa, %.2f contacts per particle\n", e,
                 2.0 * relax.diagnostics().particle_contacts / static_cast<double>(n));
  }
  SceneConfig stiff = benchmark_scene(side);
  for (auto& v : p.v) v.setZero();
  for (auto& w : p.omega) w.setZero();
  Simulation sim(stiff, p);
  sim.run(2000);
  std::ofstream out(path);
  out.precision(17);
  double top = 0.0;
  const ParticleStore& q = sim.particles();
  for (std::size_t i = 0; i < q.size(); ++i) top = std::max(top, q.x[i].z() + q.radius[i]);
  out << "Upgrain settled bed: r = 1.5 mm, E = 29 GPa (bench/dense_bed.cc)\n\n"
      << q.size() << " atoms\n1 atom types\n\n"
      << 0.0 << " " << side << " xlo xhi\n"
      << 0.0 << " " << side << " ylo yhi\n"
      << 0.0 << " " << top + 0.02 << " zlo zhi\n\nAtoms\n\n";
  // Sorted by id, so the file does not depend on the internal order.
  std::vector<std::size_t> order(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) order[static_cast<std::size_t>(q.id[i])] = i;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    out << q.id[i] + 1 << " 1 " << 2 * q.radius[i] << " " << 2650.0 << " " << q.x[i].x() << " " << q.x[i].y()
        << " " << q.x[i].z() << "\n";
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "settle: wrote %s (side %.6f m) in %.0f s\n", path.c_str(), side, secs);
  return 0;
}

// Reads a bed written by `settle` into a simulation with the benchmark material.
// `periodic`: the same grains with periodic x and y instead of the side walls (docs/periodic.md).
std::unique_ptr<Simulation> load_bed(const std::string& path, Summation summation = Summation::deterministic,
                                     bool periodic = false) {
  std::optional<upgrain::bench::Bed> bed = upgrain::bench::read_bed(path);
  if (!bed) {
    std::fprintf(stderr, "cannot open %s\n", path.c_str());
    return nullptr;
  }
  if (periodic) bed->scene.container.periodic = {true, true, false};
  EngineOptions options;
  options.summation = summation;
  return std::make_unique<Simulation>(bed->scene, std::move(bed->particles), MPI_COMM_SELF, options);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run(const std::string& path, long steps, Summation summation, bool periodic) {
  const double baseline = current_rss_bytes();  // the process before any particle data
  std::unique_ptr<Simulation> sim = load_bed(path, summation, periodic);
  if (!sim) return 1;
  const auto n = static_cast<long>(sim->owned());  // owned grains: a periodic cell adds images
  UPGRAIN_ZERO_STATS();  // a profile holds the timed steps only (the lists are built before)
  const auto t0 = std::chrono::steady_clock::now();
  sim->run(steps);
  const double secs = seconds_since(t0);
  UPGRAIN_DUMP_STATS("steps");
  const auto d2 = sim->diagnostics();
  std::printf(
      "upgrain summation %s%s particles %ld steps %ld seconds %.4f particle_steps_per_second %.4e "
      "contacts_per_particle %.3f wall_contacts %ld peak_bytes_per_particle %.0f "
      "peak_bytes_per_particle_above_baseline %.0f neighbor_builds %ld\n",
      to_string(summation).c_str(), periodic ? " periodic_xy" : "", n, steps, secs,
      static_cast<double>(n) * steps / secs, 2.0 * d2.particle_contacts / n, d2.wall_contacts,
      peak_rss_bytes() / n, (peak_rss_bytes() - baseline) / n, d2.neighbor_builds);
  return 0;
}

// Cost of grid stress: `steps` plain steps against `evaluations` steps that
// record their contacts, each followed by all seven formulas on a 3 x 3 x 4 grid and the
// HDF5 + CSV + XDMF output of the result, all in one run. Prints the cost per contact and
// the share of a run that evaluates stress every 1,000 steps.
int stress(const std::string& path, long steps, long evaluations, const std::string& folder) {
  std::unique_ptr<Simulation> sim = load_bed(path);
  if (!sim) return 1;
  const auto n = static_cast<double>(sim->particles().size());
  sim->run(200);  // warm-up: lists built, caches hot
  auto t0 = std::chrono::steady_clock::now();
  sim->run(steps);
  const double plain = seconds_since(t0) / static_cast<double>(steps);

  io::GridStressOptions options;
  options.formulas.assign({StressFormula::weber, StressFormula::drescher, StressFormula::bagi,
                           StressFormula::de_saxce, StressFormula::nicot, StressFormula::modified_nicot,
                           StressFormula::modified_de_saxce});
  io::GridStressRecorder recorder(folder, options.formulas);
  double recorded = 0.0, evaluate = 0.0, write = 0.0;
  long contacts = 0;
  for (long e = 0; e < evaluations; ++e) {
    sim->run(10);
    t0 = std::chrono::steady_clock::now();
    sim->request_contacts();
    sim->step();
    const auto t1 = std::chrono::steady_clock::now();
    const RegularGrid grid = io::stress_grid(options, sim->particles(), sim->scene().container);
    const GridStress g =
        grid_stress(sim->particles(), sim->contacts(), grid, {sim->gravity(), sim->integrates_rotation()});
    const auto t2 = std::chrono::steady_clock::now();
    recorder.record(grid, g, sim->time(), sim->step_count());
    write += seconds_since(t2);
    evaluate += std::chrono::duration<double>(t2 - t1).count();
    recorded += std::chrono::duration<double>(t1 - t0).count();
    contacts += static_cast<long>(sim->contacts().size());
  }
  const double k = static_cast<double>(evaluations);
  recorded /= k;
  evaluate /= k;
  write /= k;
  const double per_contact = evaluate / (static_cast<double>(contacts) / k);
  const double extra = (recorded - plain) + evaluate;
  std::printf(
      "upgrain stress particles %.0f contacts %.0f plain_step_s %.4e recorded_step_s %.4e evaluation_s %.4e "
      "evaluation_ns_per_contact %.1f output_s %.4e share_every_1000_steps_compute %.4f%% "
      "share_every_1000_steps_with_output %.4f%%\n",
      n, static_cast<double>(contacts) / k, plain, recorded, evaluate, 1e9 * per_contact, write,
      100.0 * extra / (1000.0 * plain), 100.0 * (extra + write) / (1000.0 * plain));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  upgrain::dem::MpiSession mpi(argc, argv);  // the engine runs on MPI_COMM_SELF
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "settle" && argc == 4) return settle(std::atol(argv[2]), argv[3]);
  if (mode == "run" && argc >= 3)
    return run(argv[2], argc > 3 ? std::atol(argv[3]) : 2000,
               argc > 4 && std::string(argv[4]) == "fast" ? Summation::fast : Summation::deterministic,
               argc > 5 && std::string(argv[5]) == "periodic");
  if (mode == "stress" && argc >= 4)
    return stress(argv[2], argc > 4 ? std::atol(argv[4]) : 2000, argc > 5 ? std::atol(argv[5]) : 20, argv[3]);
  std::fprintf(stderr,
               "usage: bench_dense_bed settle N bed.data | run bed.data [steps [fast|deterministic "
               "[periodic]]] | stress bed.data OUT [steps [evaluations]]\n");
  return 2;
}
