// A periodic cell in simple shear (docs/periodic.md, "Shear"): the images across the gradient
// axis's faces slide along the shear axis (Lees-Edwards), the tilt remapped by whole lengths at
// the rebuilds. On any number of ranks (the shear axis in one block): the affine field of a
// contact-free gas through crossings and remaps, the bits of a sheared bed on 1, 2, 3, 4 and 8
// ranks, and the energy balance with the cell's work.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "dem/boundary/container.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "dem/stress/grid_stress.h"
#include "helpers.h"
#include "upscale/strain/deformation_fit.h"
#include "upscale/strain/periodic_kinematics.h"

using namespace upgrain;
using namespace upgrain::dem;

using test::lattice;

namespace {

// test::gas_cell() sheared at L(0, 2) = `rate` (x along z), with the given rates on the diagonal of
// L besides.
SceneConfig sheared_gas(double side, double rate, const Vec3& diagonal = Vec3::Zero()) {
  SceneConfig s = test::gas_cell(side, diagonal);
  s.cell.shear = {{0, 2}, rate};
  return s;
}

}  // namespace

// Grains that never touch, with no peculiar velocity, stay on the affine field x(t) = F x(0),
// F = h(t) h(0)^-1, through a shear strain of 1.8 (the tilt remapped twice) and a
// stretch along z: their unwrapped positions (x + h n, periodic_cell.h) within the roundings of
// their steps, their peculiar velocities exactly zero; the mean flow carried grains across the
// shear axis's faces (an affine flow crosses no face of the gradient axis: the bed below does).
TEST(ShearedCell, ContactFreeGasStaysOnTheAffineFieldThroughCrossingsAndRemaps) {
  const double side = 0.03;
  const SceneConfig s = sheared_gas(side, 60.0, Vec3(0.0, 0.0, 1.5));
  std::mt19937_64 rng(11);
  const ParticleStore p0 = lattice(5, side, 0.5e-3, 0.0, rng);
  Simulation sim(s, p0, std::vector<PlaneWall>{}, MPI_COMM_WORLD);
  const Mat3 h0 = sim.cell_matrix();
  const long steps = 3000;
  sim.run(steps);
  const Mat3 h = sim.cell_matrix();
  const Mat3 f = h * h0.inverse();
  EXPECT_GT(f(0, 2), 1.7) << "the shear strain";
  EXPECT_NEAR(f(2, 2), std::exp(1.5 * steps * s.time_step), 1e-4);
  const PeriodicCell& cell = sim.decomposition().cell();
  EXPECT_LE(std::abs(cell.shear.offset), 0.5 * cell.length(0) + 1e-3) << "remapped at the rebuilds";
  EXPECT_EQ(cell.shear.turns, 2);
  const ParticleStore all = sim.gather_sorted_by_id();
  EXPECT_EQ(sim.diagnostics().particle_contacts, 0);
  if (test::world_rank() != 0) return;
  const double q = cell.quantum.maxCoeff();
  double worst = 0.0, worst_v = 0.0;
  long crossed = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Vec3 x = unwrapped(cell, all.x[i], all.image[i]);
    worst = std::max(worst, (x - f * p0.x[i]).cwiseAbs().maxCoeff());
    worst_v = std::max(worst_v, all.v[i].cwiseAbs().maxCoeff());
    crossed += all.image[i][0] != 0 ? 1 : 0;
  }
  // Each step rounds a grain onto the grid (half a quantum) and the growth of the field carries
  // the earlier roundings (F's largest component, under 3).
  EXPECT_LE(worst, 3.0 * steps * q) << "off the affine field by more than the roundings of the steps";
  EXPECT_EQ(worst_v, 0.0) << "a peculiar velocity: the grain left the mean flow L x";
  EXPECT_GT(crossed, 20) << "the flow carried no grain across the shear axis's faces";
  // The strain's view (docs/periodic.md, "Strain over a periodic cell"): the best-fit F of the
  // grains followed from their images at t0 is the cell's F, and the best-fit L the cell's.
  const std::vector<ImageCount> at_start(all.size(), ImageCount{0, 0, 0});
  const upscale::PeriodicKinematics k = upscale::periodic_kinematics(
      cell, sim.cell_velocity_gradient(), all.id, all.x, all.v, all.image, p0.id, at_start);
  const upscale::AffineFit fit = upscale::fit_deformation_gradient(p0.x, k.x);
  const upscale::AffineFit rate = upscale::fit_velocity_gradient(k.x, k.v);
  ASSERT_TRUE(fit.valid && rate.valid);
  const double f_error = (fit.gradient - f).cwiseAbs().maxCoeff();
  const double l_error = (rate.gradient - sim.cell_velocity_gradient()).cwiseAbs().maxCoeff();
  std::printf("best-fit F - cell F: %.3g; best-fit L - cell L: %.3g /s\n", f_error, l_error);
  EXPECT_LE(f_error, 1e-12);
  EXPECT_LE(l_error, 1e-12 * sim.cell_velocity_gradient().cwiseAbs().maxCoeff());
}

// A bed of frictional grains thrown into a cell periodic along x and y over a floor, sheared
// along x with the gradient y while squeezed along x and held by a servo along y
// (test::compressing_cell_scene()): the states are bitwise those of one rank on any rank count
// (the shear axis x in one block), grains crossing the sliding faces and colliding across them.
TEST(ShearedCell, ShearedBedIsBitwiseIdenticalOnAnyRankCount) {
  SceneConfig s = test::compressing_cell_scene(300, Vec3(0.5, -0.4, -0.5));
  s.cell.shear = {{0, 1}, 25.0};
  const ParticleStore fill = fill_container(s);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  EngineOptions balanced;
  balanced.balance_interval = 300;
  test::expect_rank_independent(s, fill, walls, balanced, {}, 1500);
  Simulation sim(s, fill, walls, MPI_COMM_WORLD, balanced);
  sim.run(1500);
  EXPECT_EQ(sim.decomposition().blocks()[0], 1);
  EXPECT_GT(sim.cell_matrix()(0, 1), 0.3 * 0.03) << "sheared by 0.375";
  EXPECT_GT(sim.diagnostics().particle_contacts, 50);
  const ParticleStore all = sim.gather_sorted_by_id();
  long crossed = 0;
  for (const ImageCount& c : all.image) crossed += c[1] != 0 ? 1 : 0;
  if (test::world_rank() == 0) {
    EXPECT_GT(crossed, 5) << "grains crossed the sliding faces";
  }
}

// Grid stress over a sheared cell: the orthorhombic box is a unit cell of the sheared lattice
// (docs/periodic.md, "Shear"), so a grid over it tiles the cell. The cell's stress is the Weber
// grid stress of one grid cell that is the box, less the kinetic part; and a 2 x 2 x 2 grid's
// mean is the one cell's for Bagi's formula (each grain's share in the cell of its centroid, the
// contacts across the grid's faces, the sliding ones included, with their minimum-image
// branches), to round-off. Weber's counts only the contacts inside a cell: not additive.
TEST(ShearedCell, GridStressTilesTheShearedCell) {
  SceneConfig s = test::compressing_cell_scene(300, Vec3(0.5, -0.4, -0.5));
  s.cell.shear = {{0, 1}, 25.0};
  const ParticleStore fill = fill_container(s);
  Simulation sim(s, fill, make_open_box(s.container), MPI_COMM_WORLD);
  sim.run(1500);
  sim.request_contacts();
  sim.step();
  const Box box = sim.decomposition().cell().box;
  RegularGrid one;
  one.lo = box.lo;
  one.hi = box.hi;
  RegularGrid eight = one;
  eight.n[0] = eight.n[1] = eight.n[2] = 2;
  const GridStress g1 = sim.grid_stress(one), g8 = sim.grid_stress(eight);
  const ParticleStore all = sim.gather_sorted_by_id();
  ASSERT_GT(std::abs(sim.cell_matrix()(0, 1)), 0.3 * 0.03) << "sheared";
  if (test::world_rank() != 0) return;
  ASSERT_EQ(g1.particles[0], static_cast<long>(all.size()));
  Mat3 kinetic = Mat3::Zero();
  for (std::size_t i = 0; i < all.size(); ++i) kinetic += all.mass(i) * all.v[i] * all.v[i].transpose();
  const Mat3 weber = g1.sigma[static_cast<int>(StressFormula::weber)][0];
  const Mat3 expected = weber - kinetic / g1.cell_volume;
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 1.0);
  EXPECT_LT((sim.cell_stress() - expected).cwiseAbs().maxCoeff(), 1e-12 * scale);
  EXPECT_GT(std::abs(weber(0, 1)), 1e-3 * scale) << "a shear stress to tile";
  long external = 0;
  for (long e : g8.external_contacts) external += e;
  EXPECT_GT(external, 20) << "contacts across the grid's faces";
  const auto bagi = static_cast<int>(StressFormula::bagi);
  Mat3 mean = Mat3::Zero();
  for (std::size_t c = 0; c < 8; ++c) mean += g8.sigma[bagi][c] / 8.0;
  const Mat3& whole = g1.sigma[bagi][0];
  EXPECT_LT((mean - whole).cwiseAbs().maxCoeff(), 1e-12 * whole.cwiseAbs().maxCoeff()) << mean << "\nwhole\n"
                                                                                       << whole;
}

namespace {

// The balance error after `time` of a lattice of frictionless, undamped elastic spheres sheared
// at 40 /s and squeezed into contact, with peculiar velocities, at time step dt.
double balance_error_of_shear(double dt, double time) {
  const test::CellBalance b = test::cell_balance(sheared_gas(0.015, 40.0, Vec3(-10.0, -8.0, -6.0)), dt, time);
  EXPECT_GT(b.contacts, 50);
  EXPECT_GT(std::abs(b.work), 10.0 * b.drift);
  return b.error;
}

}  // namespace

// The cell's work, its shear stress's power included, closes the energy balance at the
// integrator's order: halving the time step divides the balance error by about four.
TEST(ShearedCell, EnergyBalanceWithTheCellsWorkIsSecondOrder) {
  const double time = 6e-3;
  const double coarse = balance_error_of_shear(4e-6, time);
  const double fine = balance_error_of_shear(2e-6, time);
  if (test::world_rank() == 0) std::printf("sheared balance error: dt 4e-6 %.3e, 2e-6 %.3e\n", coarse, fine);
  EXPECT_LT(coarse, 1e-2);
  EXPECT_GT(coarse / fine, 3.0) << coarse << " at dt, " << fine << " at dt/2";
}

// The engine refuses a shear across an axis that is not periodic, and blocks that cut the shear
// axis.
TEST(ShearedCell, ShearAcrossABoundedAxisAndBlocksAlongTheShearAxisAreRefused) {
  std::mt19937_64 rng(3);
  const ParticleStore p0 = lattice(3, 0.03, 0.5e-3, 0.0, rng);
  SceneConfig s = sheared_gas(0.03, 1.0);
  s.container.periodic = {true, true, false};
  EXPECT_THROW(Simulation(s, p0, std::vector<PlaneWall>{}, MPI_COMM_WORLD), Error);
  if (test::world_size() < 2) return;
  EngineOptions cut;
  cut.blocks = {test::world_size(), 1, 1};
  EXPECT_THROW(Simulation(sheared_gas(0.03, 1.0), p0, std::vector<PlaneWall>{}, MPI_COMM_WORLD, cut), Error);
}
