// Coarse-grained fields (docs/coarse-graining.md): their cost, the width study and the
// momentum balance in motion against the sampling interval, on one bed built here. Prints
// Markdown tables; every ratio is measured in the same run. Never timed in CI.
//
//   bench_cg_fields [grains=20000] [all|dynamic|cost|widths]
//
// The bed: monodisperse spheres of Yan and Regueiro's size (docs/stress.md) (r = 1.5 mm, 2,650 kg/m^3),
// friction 0.5 between grains and at the walls, damping ratio 0.5, deposited into a 9 cm square box (30
// diameters, so that the widest kernel still has an interior; 20,000 grains make a bed about
// 19 diameters high), soft (E = 5e7 Pa, dt = 1e-5 s)
// to keep the run short. "Dynamic" is the bed 0.06 s after the fill starts falling (grains
// colliding on the floor); "at rest" is the bed once its kinetic energy is 1e-6 of the
// potential energy released, relaxed by FIRE to 1e-9.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "dem/engine/relaxation.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "dem/time_step.h"
#include "upscale/cg/coarse_grained_fields.h"

namespace {

using namespace upgrain;
using upscale::cg::CoarseGrainedFields;
using upscale::cg::GrainState;
using upscale::cg::KernelChoice;
using upscale::cg::KernelKind;
using upscale::cg::Vec3;
using Clock = std::chrono::steady_clock;

constexpr double kRadius = 1.5e-3, kDiameter = 2 * kRadius, kBox = 0.09;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

dem::SceneConfig bed_scene(long grains) {
  dem::SceneConfig s;
  s.particles.count = grains;
  s.particles.radius = kRadius;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = kBox;
  s.fill.bottom_gap = 0.002;
  s.friction = 0.5;
  s.damping_ratio = 0.5;
  s.time_step = 1e-5;
  return s;
}

// The state of the last (recorded) step, gathered.
GrainState state_now(dem::Simulation& sim) {
  sim.request_contacts();
  sim.step();
  return upscale::cg::state_from(sim.whole_state(), sim.gather_contacts_by_id(), sim.gravity(), sim.time());
}

double bed_height(const GrainState& s) {
  double h = 0.0;
  for (const Vec3& x : s.x) h = std::max(h, x.z() + kRadius);
  return h;
}

// A regular grid of n x n x m points over the box up to height h.
std::vector<Vec3> grid_points(int n, int m, double h) {
  std::vector<Vec3> p;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        p.emplace_back((i + 0.5) * kBox / n, (j + 0.5) * kBox / n, (k + 0.5) * h / m);
  return p;
}

struct Balance {
  double residual = 0.0, rms = 0.0, rate = 0.0;  // of the largest |rho g|
};
Balance balance(const CoarseGrainedFields& f, const std::vector<Vec3>& residual, const Vec3& g) {
  Balance b;
  double weight = 0.0, sum = 0.0;
  for (std::size_t q = 0; q < f.size(); ++q) {
    weight = std::max(weight, f.density[q] * g.norm());
    b.residual = std::max(b.residual, residual[q].norm());
    b.rate = std::max(b.rate, f.momentum_rate[q].norm());
    sum += residual[q].squaredNorm();
  }
  b.residual /= weight;
  b.rate /= weight;
  b.rms = std::sqrt(sum / static_cast<double>(f.size())) / weight;
  return b;
}

const std::vector<double> kWidths{0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
const KernelKind kKernels[2] = {KernelKind::gaussian, KernelKind::lucy};

// Cost of one evaluation against the run it samples: the state gathered and the fields at M
// points, against 1,000 steps of the engine.
void cost(dem::Simulation& sim, long grains) {
  auto t0 = Clock::now();
  sim.run(1000);
  const double thousand_steps = since(t0);
  t0 = Clock::now();
  const GrainState s = state_now(sim);
  const double gather = since(t0);
  const double h = bed_height(s);
  std::printf("\n### Cost (N = %ld grains, %zu branches, %zu wall contacts; 1,000 steps take %.3f s)\n\n",
              grains, s.branches(), s.wall_contacts(), thousand_steps);
  std::printf(
      "| kernel | w/d | M points | evaluation (s) | per point (us) | share of a run evaluating every 1,000 "
      "steps |\n|---|---|---|---|---|---|\n");
  for (KernelKind kind : kKernels)
    for (double w : kWidths)
      for (int n : {30, 45}) {
        if (w > 2.0 && n > 30) continue;  // the cost is linear in M (the rows up to 2 d show it)
        const std::vector<Vec3> points = grid_points(n, n / 3, h);
        t0 = Clock::now();
        const CoarseGrainedFields f = upscale::cg::coarse_grain(s, points, KernelChoice{kind, w * kDiameter});
        const double eval = since(t0) + gather;
        std::printf("| %s | %.1f | %zu | %.4f | %.2f | %.2f %% |\n",
                    std::string(upscale::cg::name_of(kind)).c_str(), w, points.size(), eval,
                    1e6 * eval / points.size(), 100 * eval / (eval + thousand_steps));
        (void)f;
      }
}

// The residual by differences against the sampling interval, in motion.
void dynamic(const dem::SceneConfig& scene) {
  dem::Simulation sim(scene, dem::fill_container(scene));
  sim.run(6000);
  const dem::TimeStepEstimate ts = dem::estimate_time_step(scene);
  const GrainState s0 = state_now(sim);
  const std::vector<Vec3> points = grid_points(40, 8, bed_height(s0));
  std::printf("\n### Momentum balance in motion (t = %.3f s, contact duration t_c = %.3g s, dt = %g s)\n\n",
              sim.time(), ts.contact_time, scene.time_step);
  std::printf(
      "| kernel | w/d | interval (steps) | interval / t_c | largest residual / rho g | rms residual / rho g "
      "| largest d(rho v)/dt / rho g |\n|---|---|---|---|---|---|---|\n");
  std::vector<GrainState> later;
  std::vector<long> steps{1, 2, 5, 10, 20, 50, 100};
  long done = 0;
  for (long k : steps) {
    sim.run(k - done - 1);
    later.push_back(state_now(sim));
    done = k;
  }
  for (KernelKind kind : kKernels)
    for (double w : {0.5, 1.0, 2.0}) {
      const KernelChoice kc{kind, w * kDiameter};
      const CoarseGrainedFields f0 = upscale::cg::coarse_grain(s0, points, kc);
      const Balance exact = balance(f0, f0.residual, s0.gravity);
      std::printf("| %s | %.1f | (accelerations) | 0 | %.2e | %.2e | %.2e |\n",
                  std::string(upscale::cg::name_of(kind)).c_str(), w, exact.residual, exact.rms, exact.rate);
      for (std::size_t i = 0; i < steps.size(); ++i) {
        const double interval = later[i].time - s0.time;
        const CoarseGrainedFields f1 = upscale::cg::coarse_grain(later[i], points, kc);
        const Balance b = balance(f0, upscale::cg::residual_by_differences(f0, f1, interval), s0.gravity);
        std::printf("| %s | %.1f | %ld | %.3f | %.2e | %.2e | %.2e |\n",
                    std::string(upscale::cg::name_of(kind)).c_str(), w, steps[i], interval / ts.contact_time,
                    b.residual, b.rms, b.rate);
      }
    }
}

// The width study at rest: residual, lateral smoothness, agreement with Bagi's cell
// averages, cost.
void widths(dem::Simulation& sim) {
  const GrainState s = state_now(sim);
  const double h = bed_height(s);
  // Bagi's cell averages on cubes of about 10 mm (a box kernel of standard deviation
  // 10 mm / sqrt(12) = 0.96 d along each axis), compared over the cells that touch neither a
  // wall nor the floor nor the bed's top.
  dem::RegularGrid grid;
  grid.lo = dem::Vec3(0, 0, 0);
  grid.hi = dem::Vec3(kBox, kBox, h);
  grid.n[0] = grid.n[1] = 9;
  grid.n[2] = std::max(3, static_cast<int>(std::round(h / 0.01)));
  const int nz = grid.n[2];
  const dem::GridStress bagi = sim.grid_stress(grid);
  const int sub = 6;  // the cell mean of a field: the mean of 6^3 points per cell
  std::vector<Vec3> centres, cell_points;
  std::vector<int> interior;
  for (int c = 0; c < grid.num_cells(); ++c) {
    const int i = c % 9, j = (c / 9) % 9, k = c / 81;
    if (i == 0 || j == 0 || i == 8 || j == 8 || k == 0 || k == nz - 1) continue;
    interior.push_back(c);
    centres.push_back(grid.cell_centre(c));
    const dem::Vec3 size = (grid.hi - grid.lo).cwiseQuotient(dem::Vec3(9, 9, nz));
    const dem::Vec3 lo = grid.cell_centre(c) - 0.5 * size;
    for (int a = 0; a < sub; ++a)
      for (int b = 0; b < sub; ++b)
        for (int e = 0; e < sub; ++e)
          cell_points.push_back(
              lo + size.cwiseProduct(dem::Vec3((e + 0.5) / sub, (b + 0.5) / sub, (a + 0.5) / sub)));
  }
  std::printf(
      "\n### Width study at rest (%zu grains, bed %.1f mm = %.1f d high, %zu branches; Bagi on 9 x 9 x %d "
      "cells, %zu inner ones compared)\n\n",
      s.grains(), 1e3 * h, h / kDiameter, s.branches(), nz, interior.size());
  std::printf(
      "| kernel | w/d | largest residual / rho g | spread of s_zz across z = h/2 (interior) | CG at cell "
      "centre vs "
      "Bagi | CG cell mean vs Bagi | cost per point (us) |\n|---|---|---|---|---|---|---|\n");
  for (KernelKind kind : kKernels)
    for (double w : kWidths) {
      const KernelChoice kc{kind, w * kDiameter};
      const double cutoff = upscale::cg::cutoff_of(kc);
      std::vector<Vec3> level;
      for (double y = cutoff; y <= kBox - cutoff; y += kDiameter / 4)
        for (double x = cutoff; x <= kBox - cutoff; x += kDiameter / 4) level.emplace_back(x, y, 0.5 * h);
      const std::vector<Vec3> all_points = grid_points(45, 8, h);
      auto t0 = Clock::now();
      const CoarseGrainedFields f = upscale::cg::coarse_grain(s, all_points, kc);
      const double per_point = 1e6 * since(t0) / all_points.size();
      const Balance b = balance(f, f.residual, s.gravity);
      double spread = std::nan("");
      if (!level.empty()) {
        const CoarseGrainedFields fl = upscale::cg::coarse_grain(s, level, kc);
        double lo = INFINITY, hi = -INFINITY, sum = 0;
        for (const auto& m : fl.stress) {
          lo = std::min(lo, m(2, 2));
          hi = std::max(hi, m(2, 2));
          sum += m(2, 2);
        }
        spread = (hi - lo) / std::abs(sum / fl.size());
      }
      const CoarseGrainedFields fc = upscale::cg::coarse_grain(s, centres, kc);
      const CoarseGrainedFields fm = upscale::cg::coarse_grain(s, cell_points, kc);
      double d_centre = 0, d_mean = 0, norm = 0;
      for (std::size_t k = 0; k < interior.size(); ++k) {
        const double ref = bagi[dem::StressFormula::bagi][interior[k]](2, 2);
        double mean = 0;
        for (int p = 0; p < sub * sub * sub; ++p) mean += fm.stress[k * sub * sub * sub + p](2, 2);
        mean /= sub * sub * sub;
        d_centre += std::pow(fc.stress[k](2, 2) - ref, 2);
        d_mean += std::pow(mean - ref, 2);
        norm += ref * ref;
      }
      std::printf("| %s | %.1f | %.1e | %s | %.3f | %.3f | %.2f |\n",
                  std::string(upscale::cg::name_of(kind)).c_str(), w, b.residual,
                  std::isnan(spread) ? "no interior" : (std::to_string(spread).substr(0, 5)).c_str(),
                  std::sqrt(d_centre / norm), std::sqrt(d_mean / norm), per_point);
    }
}

void run(int argc, char** argv) {
  const long grains = argc > 1 ? std::atol(argv[1]) : 20000;
  const std::string part = argc > 2 ? argv[2] : "all";
  const dem::SceneConfig scene = bed_scene(grains);
  std::printf("# Coarse-grained fields: cost, width study, balance in motion (%ld grains)\n", grains);
  if (part == "all" || part == "dynamic") dynamic(scene);
  if (part == "dynamic") return;
  dem::Simulation sim(scene, dem::fill_container(scene));
  for (long steps = 0; steps < 400000; steps += 2000) {
    sim.run(2000);
    if (steps > 20000 && sim.kinetic_to_released() < 1e-6) break;
  }
  if (part == "all" || part == "cost") cost(sim, grains);
  if (part == "cost") return;
  const dem::RelaxationResult relaxed = dem::relax_to_equilibrium(sim, {});
  std::printf("\n(relaxed by FIRE in %ld steps to %.1e of m g)\n", relaxed.steps, relaxed.max_force_residual);
  widths(sim);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  run(argc, argv);  // the engine is gone before MPI_Finalize
  MPI_Finalize();
  return 0;
}
