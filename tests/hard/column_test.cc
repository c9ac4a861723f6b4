// Stiffness extremes and a tall column: single-file columns of spheres, placed touching on the
// floor and let settle under gravity (FIRE, dem/engine/relaxation.h). At rest each contact
// carries the weight above it, so each overlap is Hertz's for that load (Johnson 1985, eq.
// 4.23): delta = (3 F / (4 E* sqrt(R*)))^(2/3), R* = r at the floor and r/2 between grains.
// The floor force is the column's weight, and so is sigma_zz at the floor from the grid stress
// (Bagi's formula, docs/stress.md) times the container's footprint. Then the column is held by
// the plain dynamics (damping on) and must not creep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../common/scenes.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/engine/relaxation.h"
#include "dem/engine/simulation.h"
#include "dem/time_step.h"
#include "full_size.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

struct ColumnCase {
  int n;     // grains in the column
  double r;  // m
  Material material;
  long hold_steps;  // plain dynamics after the relaxation
};

struct ColumnResult {
  double worst_overlap_error = 0.0;  // max over contacts of |delta - delta_Hertz| / delta_Hertz
  double floor_overlap_ratio = 0.0;  // floor overlap / r
  double floor_force_error = 0.0;    // |F_floor - W| / W
  double creep = 0.0;                // largest displacement while held, / floor overlap
  // Grid stress (Bagi) in kLayers layers over the footprint: the bottom layer's sigma_zz
  // against the weight at its mid-height over the area, and the profile extrapolated to the
  // floor against the weight over the area; relative errors.
  double bottom_layer_error = 0.0;
  double floor_stress_error = 0.0;
  double time_step = 0.0, safe_step = 0.0;
  long relaxation_steps = 0;
};

constexpr int kLayers = 5;  // of the stress grid; the columns' counts are multiples of it

ColumnResult settle_column(const ColumnCase& c) {
  SceneConfig s = test::bare_scene(1.0);
  s.particles.material = c.material;
  s.particles.radius = c.r;
  s.particles.count = c.n;
  s.effects.gravity = true;
  s.effects.damping = true;
  s.damping_ratio = 0.7;
  s.container.lx = s.container.ly = 4 * c.r;  // the side walls are never touched
  s.fill.bottom_gap = 0.0;
  ColumnResult out;
  out.safe_step = estimate_time_step(s).safe_step;
  s.time_step = out.time_step = 0.9 * out.safe_step;
  ParticleStore p;
  for (int k = 0; k < c.n; ++k)  // touching exactly: no overlap at the start
    p.add_sphere(k, c.r, c.material.density, Vec3(2 * c.r, 2 * c.r, c.r + 2 * c.r * k), Vec3::Zero(),
                 Vec3::Zero());
  Simulation sim(s, p);
  RelaxationOptions ro;
  ro.max_steps = 400000;
  const RelaxationResult rr = relax_to_equilibrium(sim, ro);
  EXPECT_TRUE(rr.converged) << "residual " << rr.max_force_residual;
  out.relaxation_steps = rr.steps;

  const ParticleStore at_rest = sim.gather_sorted_by_id();
  const double m = at_rest.mass(0), g = s.gravity;
  const HertzNormal::Constants cm = HertzNormal::constants(c.material, {}).pair;
  auto error_of = [&](double overlap, double e_star, double r_star, double load) {
    const double hertz = hertz::overlap_for_force(e_star, r_star, load);
    out.worst_overlap_error = std::max(out.worst_overlap_error, std::abs(overlap - hertz) / hertz);
  };
  const double floor_overlap = c.r - at_rest.x[0].z();
  error_of(floor_overlap, cm.e_star, c.r, c.n * m * g);
  for (int k = 0; k + 1 < c.n; ++k)
    error_of(2 * c.r - (at_rest.x[k + 1].z() - at_rest.x[k].z()), cm.e_star, c.r / 2, (c.n - 1 - k) * m * g);
  out.floor_overlap_ratio = floor_overlap / c.r;
  const double weight = c.n * m * g;
  out.floor_force_error = std::abs(-sim.wall_forces()[0].z() - weight) / weight;

  // The grid stress of the relaxed column, as the driver computes it (Stress/box = auto: the
  // footprint from the floor to the top of the highest grain), in layers of n / kLayers grains.
  // The mean of sigma_zz over a layer is, at rest, the weight at the layer's mid-height over
  // the area A (the layer's own weight counts half: docs/stress.md, "Dynamic terms: derivation",
  // summed over its grains); the layers' means are linear in z, so the bottom two give the
  // floor's value, sigma(0) = (3 sigma_1 - sigma_2) / 2 = -W / A.
  sim.request_contacts();
  sim.step();
  RegularGrid grid;
  grid.hi = Vec3(s.container.lx, s.container.ly, sim.particles().x[0].z());
  for (int k = 0; k < sim.owned(); ++k) grid.hi.z() = std::max(grid.hi.z(), sim.particles().x[k].z() + c.r);
  grid.n[2] = kLayers;
  const GridStress stress = sim.grid_stress(grid);
  const double area = s.container.lx * s.container.ly;
  const double s1 = stress[StressFormula::bagi][0](2, 2), s2 = stress[StressFormula::bagi][1](2, 2);
  const double layer_weight = weight / kLayers;
  out.bottom_layer_error = std::abs(-s1 * area - (weight - 0.5 * layer_weight)) / weight;
  out.floor_stress_error = std::abs(-0.5 * (3 * s1 - s2) * area - weight) / weight;

  sim.run(c.hold_steps);
  const ParticleStore held = sim.gather_sorted_by_id();
  for (int k = 0; k < c.n; ++k)
    out.creep = std::max(out.creep, (held.x[k] - at_rest.x[k]).norm() / floor_overlap);
  std::printf(
      "%d grains, E %.3g Pa: dt %.3g s (0.9 safe), relaxed in %ld steps; floor overlap %.3e r; worst overlap "
      "vs Hertz %.2e; floor force vs weight %.2e; grid sigma_zz (Bagi, %d layers): bottom layer vs weight at "
      "its mid-height %.2e, at the floor vs weight %.2e; creep over %ld steps %.2e of the floor overlap\n",
      c.n, c.material.youngs_modulus, out.time_step, out.relaxation_steps, out.floor_overlap_ratio,
      out.worst_overlap_error, out.floor_force_error, kLayers, out.bottom_layer_error, out.floor_stress_error,
      c.hold_steps, out.creep);
  return out;
}

// The relaxation stops when every grain's out-of-balance force is below 1e-9 of its weight
// (RelaxationOptions::force_tolerance): a contact's load is then known to n 1e-9 of its value
// for n grains above it, its overlap to 2/3 of that. The bound, 1e-7, holds that for n up to 100.
constexpr double kLoadTolerance = 1e-7;

// The grid stress against the weight over the area: Bagi's sums run over the branches from the
// centres to the contact points, which are shorter than r by half a pair's overlap (at most
// about the floor overlap, a pair's overlap being twice the floor's under the same load) or by
// the floor overlap itself, and the layers are shorter than their grains' diameters by the
// overlaps between them. The bottom layer's value is therefore right to within the floor
// overlap over r, and the floor's value, 3/2 of one layer's less 1/2 of the next, to twice it.
void expect_floor_stress_is_weight_per_area(const ColumnResult& r) {
  EXPECT_LT(r.bottom_layer_error, r.floor_overlap_ratio);
  EXPECT_LT(r.floor_stress_error, 2 * r.floor_overlap_ratio);
}

}  // namespace

TEST(HardStiffness, SoftGrainsOfE1e5PaSettleToHertzOverlaps) {
  const ColumnResult r = settle_column({5, 1.5e-3, {2650.0, 1e5, 0.25}, 20000});
  EXPECT_GT(r.floor_overlap_ratio, 0.01);  // soft: overlaps of a few percent
  EXPECT_LT(r.floor_overlap_ratio, 0.1);
  EXPECT_LT(r.worst_overlap_error, kLoadTolerance);
  EXPECT_LT(r.floor_force_error, kLoadTolerance);
  expect_floor_stress_is_weight_per_area(r);
  EXPECT_LT(r.creep, 1e-6);
}

TEST(HardStiffness, SteelGrainsOfE2e11PaSettleToHertzOverlaps) {
  const ColumnResult r = settle_column({5, 1.5e-3, {7850.0, 2e11, 0.3}, 20000});
  EXPECT_LT(r.floor_overlap_ratio, 1e-4);  // stiff: tiny overlaps
  EXPECT_LT(r.worst_overlap_error, kLoadTolerance);
  EXPECT_LT(r.floor_force_error, kLoadTolerance);
  expect_floor_stress_is_weight_per_area(r);
  EXPECT_LT(r.creep, 1e-6);
}

TEST(HardColumn, HundredGrainColumnCarriesItsWeightWithHertzOverlaps) {
  // Held for 1e5 steps at full size (bench/hard_cases.sh), 2e4 in CI.
  const ColumnResult r = settle_column({100, 1.5e-3, {2650.0, 5e9, 0.25}, test::hard_size(20000, 100000)});
  EXPECT_LT(r.worst_overlap_error, kLoadTolerance);
  EXPECT_LT(r.floor_force_error, kLoadTolerance);
  expect_floor_stress_is_weight_per_area(r);
  EXPECT_LT(r.creep, 1e-6);
}
