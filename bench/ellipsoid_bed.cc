// Ellipsoid dense-bed benchmark: the foundation benchmark's dense
// bed (bench/dense_bed.cc: r = 1.5 mm, 2,650 kg/m^3, E = 29 GPa, nu = 0.25, mu = 0.5,
// zeta = 0.5, dt = 1e-6 s) built twice in one run, once of spheres and once of ellipsoids
// 1:0.8:0.6 of the same volume-equivalent radius (a = 1.5 mm / cbrt(0.48)) in uniformly
// random orientations. Each bed is deposited soft, stiffened to 29 GPa in short steps (4,000
// steps per stage, 10,000 at the end, at damping ratio 1), then timed over `steps` steps from
// the settled state, in `rounds` rounds that alternate the two beds (spheres first in odd
// rounds, ellipsoids first in even ones), so that a change of load on a shared machine falls on
// both alike. Prints particle-steps per second of both (the best round of each), the ratio of
// an ellipsoid particle-step to a sphere one from those best rounds (target: at most 4) and the
// spread of the per-round ratios, narrow-phase tests per second (pairs past the bounding
// spheres: still apart by an earlier proof, proven apart, or solved), and Newton steps per
// solve.
//   bench_ellipsoid_bed [N [steps [cache_dir [rounds [phase [summation]]]]]]
//                                     (defaults 2000, 2000, no cache, 5, bed, deterministic)
// `phase` = deposition times a flow instead of the settled bed: both fills falling and piling
// up (soft grains, E = 1e8 Pa, one time step for both, 0.8 of the ellipsoids' safe step), timed
// from t = 0.15 s (the pile forming on the floor), where grains move, turn and collide.
// With `cache_dir`, the settled beds are written there on the first run and read back on
// later ones (same N), so repeated timings and callgrind runs skip the settling. Under
// callgrind (`valgrind --tool=callgrind`) there is one round, and each bed's timed steps are a
// profile file of their own (`.1` spheres, `.2` ellipsoids; the counters are zeroed before).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <string>

#include "bench/callgrind_marks.h"
#include "bench/dense_bed_scene.h"
#include "dem/engine/relaxation.h"
#include "dem/engine/simulation.h"
#include "dem/parallel/mpi_start.h"
#include "dem/scene/fill.h"
#include "dem/time_step.h"

#include <algorithm>
#include <memory>
#include <vector>

using namespace upgrain::dem;

namespace {

// The settled bed as raw arrays (a benchmark's private cache, not a file format; the
// element types are plain numbers and fixed-size Eigen types).
template <class T>
void write_array(std::ofstream& out, const std::vector<T>& a) {
  const std::size_t n = a.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  out.write(reinterpret_cast<const char*>(a.data()), static_cast<std::streamsize>(n * sizeof(T)));
}

template <class T>
bool read_array(std::ifstream& in, std::vector<T>& a) {
  std::size_t n = 0;
  if (!in.read(reinterpret_cast<char*>(&n), sizeof n)) return false;
  a.resize(n);
  return static_cast<bool>(
      in.read(reinterpret_cast<char*>(a.data()), static_cast<std::streamsize>(n * sizeof(T))));
}

template <class F>
void for_each_array(ParticleStore& p, F&& f) {
  f(p.id);
  f(p.radius);
  f(p.inv_mass);
  f(p.inv_inertia);
  f(p.x);
  f(p.v);
  f(p.omega);
  f(p.force);
  f(p.torque);
  f(p.shape);
  f(p.semi_axes);
  f(p.orientation);
  f(p.inertia_body);
}

// The summation of the timed beds (docs/architecture.md).
EngineOptions timed_options;

// A settled bed ready to be timed, and what its timed steps gave.
struct Bed {
  const char* what = "";
  long n = 0;
  std::unique_ptr<Simulation> sim;
  ContactSolverStats before;  // the counters before the first timed step
  double seconds = 0.0;       // all timed steps
  std::vector<double> round_rates;
};

// Times `steps` steps of a bed (particle-steps per second), collected by callgrind if it runs.
double time_steps(Bed& b, long steps) {
  UPGRAIN_ZERO_STATS();  // a profile holds the timed steps only (dumped by the caller)
  const auto t0 = std::chrono::steady_clock::now();
  b.sim->run(steps);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  b.seconds += s;
  b.round_rates.push_back(static_cast<double>(b.n) * static_cast<double>(steps) / s);
  return b.round_rates.back();
}

// Deposits `n` grains of `shapes` (empty: spheres of radius r) soft and stiffens them to the
// benchmark material.
ParticleStore settle(long n, double r, const std::vector<GrainShape>& shapes, double side);

// The soft scene of the settling, filled and not yet fallen.
SceneConfig soft_scene(long n, double r, const std::vector<GrainShape>& shapes, double side) {
  SceneConfig s = upgrain::bench::benchmark_scene(side);
  s.particles.count = n;
  s.particles.radius = r;
  s.particles.shapes = shapes;
  s.fill.bottom_gap = 0.002;
  s.fill.position_jitter = 0.5;
  s.particles.material.youngs_modulus = 1e8;
  s.time_step = 0.8 * estimate_time_step(s).safe_step;
  return s;
}

// A deposition in flow: the fill run to t = 0.15 s at time step `dt`, ready for timing.
Bed flowing(long n, double r, const std::vector<GrainShape>& shapes, double dt) {
  const double side = std::cbrt(n * 4.0 / 3.0 * std::numbers::pi * std::pow(1.5e-3, 3) / 0.6);
  SceneConfig s = soft_scene(n, r, shapes, side);
  s.time_step = dt;
  Bed b;
  b.what = shapes.empty() ? "spheres" : "ellipsoids";
  b.n = n;
  b.sim = std::make_unique<Simulation>(s, fill_container(s), MPI_COMM_SELF, timed_options);
  b.sim->run(std::lround(0.15 / dt));
  b.before = b.sim->contact_solver_stats();
  return b;
}

// The settled bed (from the cache or settled now), stiff and warmed up for timing.
Bed prepare(long n, double r, const std::vector<GrainShape>& shapes, const std::string& cache_dir) {
  const double side = std::cbrt(n * 4.0 / 3.0 * std::numbers::pi * std::pow(1.5e-3, 3) / 0.6);
  const char* what = shapes.empty() ? "spheres" : "ellipsoids";
  ParticleStore p;
  const std::string cache =
      cache_dir.empty() ? std::string() : cache_dir + "/" + what + "_" + std::to_string(n) + ".bin";
  bool cached = false;
  if (!cache.empty()) {
    std::ifstream in(cache, std::ios::binary);
    cached = static_cast<bool>(in);
    for_each_array(p, [&](auto& a) { cached = cached && read_array(in, a); });
    if (cached) std::fprintf(stderr, "%s: settled bed read from %s\n", what, cache.c_str());
  }
  if (!cached) {
    p = settle(n, r, shapes, side);
    if (!cache.empty()) {
      std::ofstream out(cache, std::ios::binary);
      for_each_array(p, [&](auto& a) { write_array(out, a); });
    }
  }
  SceneConfig stiff = upgrain::bench::benchmark_scene(side);
  stiff.particles.shapes = shapes;
  if (estimate_time_step(stiff).safe_step < stiff.time_step)
    std::fprintf(stderr, "%s: note: dt = 1e-6 s is above the safe step %.2e s\n", what,
                 estimate_time_step(stiff).safe_step);
  for (auto& v : p.v) v.setZero();
  for (auto& w : p.omega) w.setZero();
  Bed b;
  b.what = what;
  b.n = n;
  b.sim = std::make_unique<Simulation>(stiff, p, MPI_COMM_SELF, timed_options);
  b.sim->run(200);  // lists built, caches warm
  b.before = b.sim->contact_solver_stats();
  return b;
}

ParticleStore settle(long n, double r, const std::vector<GrainShape>& shapes, double side) {
  const SceneConfig s = soft_scene(n, r, shapes, side);
  const char* what = shapes.empty() ? "spheres" : "ellipsoids";
  Simulation soft(s, fill_container(s));
  for (long k = 1; k * s.time_step <= 1.0; ++k) {
    soft.step();
    if (k % 2000 == 0 && k * s.time_step > 0.1 && soft.kinetic_to_released() < 1e-5) break;
  }
  std::fprintf(stderr, "%s: soft bed at rest after %.3f s\n", what, soft.time());
  ParticleStore p = soft.particles();
  for (double e : {4e8, 1.6e9, 6.4e9, 29e9}) {
    SceneConfig stage = s;
    stage.particles.material.youngs_modulus = e;
    stage.damping_ratio = 1.0;
    stage.time_step = 0.8 * estimate_time_step(stage).safe_step;
    for (auto& v : p.v) v.setZero();
    for (auto& w : p.omega) w.setZero();
    Simulation relax(stage, p);
    // Short stages (the timing, not the packing, is measured): both beds get the same.
    relax.run(e < 29e9 ? 4000 : 10000);
    p = relax.particles();
    std::fprintf(stderr, "%s: relaxed at E = %.2g Pa (dt %.2e s)\n", what, e, stage.time_step);
  }
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  upgrain::dem::MpiSession mpi(argc, argv);  // the engine runs on MPI_COMM_SELF
  const long n = argc > 1 ? std::atol(argv[1]) : 2000;
  const long steps = argc > 2 ? std::atol(argv[2]) : 2000;
  const std::string cache_dir = argc > 3 ? argv[3] : "";
  const long rounds = UPGRAIN_ON_VALGRIND() ? 1 : std::max(1L, argc > 4 ? std::atol(argv[4]) : 5L);
  const bool deposition = argc > 5 && std::string(argv[5]) == "deposition";
  if (argc > 6 && std::string(argv[6]) == "fast") timed_options.summation = Summation::fast;
  const double r = 1.5e-3;
  const GrainShape shape = ellipsoid_grain(0.8, 0.6);
  const double a = r / std::cbrt(0.8 * 0.6);
  Bed spheres, ellipsoids;
  if (deposition) {
    const double side = std::cbrt(n * 4.0 / 3.0 * std::numbers::pi * std::pow(1.5e-3, 3) / 0.6);
    const double dt = soft_scene(n, a, {shape}, side).time_step;
    spheres = flowing(n, r, {}, dt);
    ellipsoids = flowing(n, a, {shape}, dt);
  } else {
    spheres = prepare(n, r, {}, cache_dir);
    ellipsoids = prepare(n, a, {shape}, cache_dir);
  }
  const long per_round = std::max(1L, steps / rounds);
  std::vector<double> ratios;
  for (long k = 0; k < rounds; ++k) {
    if (UPGRAIN_ON_VALGRIND()) {  // one profile per bed
      time_steps(spheres, per_round);
      UPGRAIN_DUMP_STATS("spheres");
      time_steps(ellipsoids, per_round);
      UPGRAIN_DUMP_STATS("ellipsoids");
    } else if (k % 2 == 0) {
      time_steps(spheres, per_round);
      time_steps(ellipsoids, per_round);
    } else {
      time_steps(ellipsoids, per_round);
      time_steps(spheres, per_round);
    }
    ratios.push_back(spheres.round_rates.back() / ellipsoids.round_rates.back());
  }
  const double best_spheres = *std::max_element(spheres.round_rates.begin(), spheres.round_rates.end());
  const double best_ellipsoids =
      *std::max_element(ellipsoids.round_rates.begin(), ellipsoids.round_rates.end());
  std::sort(ratios.begin(), ratios.end());
  ContactSolverStats st = ellipsoids.sim->contact_solver_stats();
  st -= ellipsoids.before;
  auto contacts = [](const Bed& b) {
    return 2.0 * static_cast<double>(b.sim->diagnostics().particle_contacts) / static_cast<double>(b.n);
  };
  const double tests = static_cast<double>(st.calls + st.proven_apart + st.still_apart);
  std::printf(
      "upgrain ellipsoid_bed phase %s particles %ld steps %ld rounds %ld sphere_particle_steps_per_second "
      "%.4e "
      "ellipsoid_particle_steps_per_second %.4e cost_ratio %.3f round_ratio_min %.3f round_ratio_median %.3f "
      "round_ratio_max %.3f sphere_contacts_per_particle %.3f ellipsoid_contacts_per_particle %.3f "
      "narrow_phase_tests_per_second %.4e solver_calls_per_second %.4e still_apart_share %.3f "
      "proven_apart_share %.3f newton_steps_per_call %.3f warm_share %.4f fallbacks %lld failures %lld\n",
      deposition ? "deposition" : "bed", n, per_round * rounds, rounds, best_spheres, best_ellipsoids,
      best_spheres / best_ellipsoids, ratios.front(), ratios[ratios.size() / 2], ratios.back(),
      contacts(spheres), contacts(ellipsoids), tests / ellipsoids.seconds,
      static_cast<double>(st.calls) / ellipsoids.seconds, static_cast<double>(st.still_apart) / tests,
      static_cast<double>(st.proven_apart) / tests,
      static_cast<double>(st.newton_iterations) / static_cast<double>(std::max<std::int64_t>(st.calls, 1)),
      static_cast<double>(st.warm_starts) / static_cast<double>(std::max<std::int64_t>(st.calls, 1)),
      static_cast<long long>(st.fallbacks), static_cast<long long>(st.failures));
  return 0;
}
