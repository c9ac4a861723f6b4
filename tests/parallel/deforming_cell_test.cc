// A periodic cell that deforms by a diagonal velocity gradient (docs/periodic.md, "A cell that
// deforms"), on any number of ranks: the affine field of a contact-free gas, the bits of a
// compressing bed on 1, 2, 3, 4 and 8 ranks, a servo to a target pressure, and the energy
// balance with the cell's work.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "dem/boundary/container.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

using test::gas_cell;
using test::lattice;

// Grains that never touch, with no peculiar velocity, stay on the affine field x(t) = F(t) x(0),
// F = h(t) h(0)^-1, to round-off: each step's drift and the cell's faces take the same map
// x + dt L x onto the grid, so a grain is off F x(0) by the roundings of its steps, at most a
// quantum each (q = 2^-52 of the grid's span), times the growth. Their peculiar velocities (the
// store's, relative to the mean flow L x) stay zero.
TEST(DeformingCell, ContactFreeGasStaysOnTheAffineField) {
  const double side = 0.03;
  const SceneConfig s = gas_cell(side, Vec3(-4.0, -1.5, 2.5));
  std::mt19937_64 rng(11);
  const ParticleStore p0 = lattice(5, side, 0.5e-3, 0.0, rng);
  Simulation sim(s, p0, std::vector<PlaneWall>{}, MPI_COMM_WORLD);
  const Mat3 h0 = sim.cell_matrix();
  const long steps = 3000;
  sim.run(steps);
  const Mat3 h = sim.cell_matrix();
  const Mat3 f = h * h0.inverse();
  EXPECT_NEAR(f(0, 0), std::exp(-4.0 * steps * s.time_step), 2e-4) << "h' = L h, to the scheme's order";
  EXPECT_LT(f(0, 0), 0.9);
  EXPECT_GT(f(2, 2), 1.07);
  const ParticleStore all = sim.gather_sorted_by_id();
  EXPECT_EQ(sim.diagnostics().particle_contacts, 0);
  if (test::world_rank() != 0) return;
  const PeriodicCell& cell = sim.decomposition().cell();
  const double q = cell.quantum.maxCoeff();
  double worst = 0.0, worst_v = 0.0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Vec3 expected = f * p0.x[i];
    const Vec3 x = unwrapped(cell, all.x[i], all.image[i]);
    worst = std::max(worst, (x - expected).cwiseAbs().maxCoeff());
    worst_v = std::max(worst_v, all.v[i].cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst, 2.0 * steps * q) << "off the affine field by more than the roundings of the steps";
  EXPECT_EQ(worst_v, 0.0) << "a peculiar velocity: the grain left the mean flow L x";
  EXPECT_GT(worst, 0.0);  // the comparison is not of a grain with itself
}

// A bed over a floor in a cell periodic along x and y, squeezed along x at a prescribed rate and
// along y by a servo (test::compressing_cell_scene()): the states are bitwise those of one rank
// on any rank count, grains crossing the moving faces.
TEST(DeformingCell, CompressingPeriodicBedIsBitwiseIdenticalOnAnyRankCount) {
  const SceneConfig s = test::compressing_cell_scene(300, Vec3(0.5, -0.4, -0.5));
  const ParticleStore fill = fill_container(s);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  // The load balance moves the planes at its rebuilds; between them they follow the cell.
  EngineOptions balanced;
  balanced.balance_interval = 300;
  test::expect_rank_independent(s, fill, walls, balanced, {}, 1500);
  Simulation sim(s, fill, walls, MPI_COMM_WORLD, balanced);
  std::set<double> servo_rates;
  for (int k = 0; k < 1500; ++k) {
    sim.step();
    servo_rates.insert(sim.cell_velocity_gradient()(1, 1));
  }
  EXPECT_GT(servo_rates.size(), 100u) << "the servo set L_yy from the cell's stress";
  EXPECT_LT(sim.cell_matrix()(0, 0), 0.03 * std::exp(-3.0 * 0.015) + 1e-9);
  EXPECT_GT(sim.diagnostics().particle_contacts, 50);
  const ParticleStore all = sim.gather_sorted_by_id();
  long crossed = 0;
  for (const ImageCount& c : all.image) crossed += (c[0] != 0 || c[1] != 0) ? 1 : 0;
  if (test::world_rank() == 0) {
    EXPECT_GT(crossed, 20) << "grains crossed the moving faces";
  }
}

// A servo on the three axes squeezes a loose gas of 216 frictional spheres into a packing at the
// target pressure. The servo's fixed point is the target: what is left is the packing's own
// fluctuation, which the damping takes out; averaged over the last 2,000 steps each diagonal
// stress is within 2 % of the target, and the packing's solid fraction is that of a jammed
// frictional packing (above 0.5).
TEST(DeformingCell, ServoBringsAPackingToItsTargetPressure) {
  // 32,000 steps: the physics is checked once, on one rank (the same figures on 2, 4 and 8 when
  // measured); a servo's rank independence is CompressingPeriodicBed's.
  if (test::world_size() > 1) GTEST_SKIP() << "one rank's test";
  const double side = 0.015, r = 0.9e-3, target = 2e4;
  SceneConfig s = gas_cell(side, Vec3::Zero());
  s.time_step = 4e-6;
  s.damping_ratio = 0.5;
  for (int d = 0; d < 3; ++d) s.cell.axis[d] = {CellAxisMode::servo, 0.0, target, 10.0 / target, 10.0};
  std::mt19937_64 rng(5);
  const ParticleStore p0 = lattice(6, side, r, 0.05, rng);
  Simulation sim(s, p0, std::vector<PlaneWall>{}, MPI_COMM_WORLD);
  sim.run(30000);
  Vec3 mean = Vec3::Zero();
  const int window = 2000;
  for (int k = 0; k < window; ++k) {
    sim.step();
    mean -= sim.cell_stress().diagonal() / window;
  }
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(mean[d], target, 0.02 * target) << "axis " << d;
  const Mat3 h = sim.cell_matrix();
  const double phi = 216 * 4.0 / 3.0 * M_PI * r * r * r / h.determinant();
  const long contacts = sim.diagnostics().particle_contacts;  // collective: on every rank
  if (test::world_rank() == 0)
    std::printf("servo: mean -sigma %.1f %.1f %.1f Pa (target %.0f), phi %.4f, contacts %ld\n", mean[0],
                mean[1], mean[2], target, phi, contacts);
  EXPECT_GT(phi, 0.5);
  EXPECT_LT(phi, 0.74);
}

// The engine refuses a deforming axis that is not periodic.
TEST(DeformingCell, DeformingAxisThatIsNotPeriodicIsRefused) {
  SceneConfig s = gas_cell(0.03, Vec3(-1.0, 0.0, 0.0));
  s.container.periodic = {false, true, true};
  std::mt19937_64 rng(3);
  const ParticleStore p0 = lattice(3, 0.03, 0.5e-3, 0.0, rng);
  EXPECT_THROW(Simulation(s, p0, std::vector<PlaneWall>{}, MPI_COMM_WORLD), Error);
}

namespace {

// The balance error after `time` of a lattice of frictionless, undamped elastic spheres squeezed
// into contact at -10/s, with peculiar velocities, at time step dt.
double balance_error_of_compression(double dt, double time) {
  const test::CellBalance b = test::cell_balance(gas_cell(0.015, Vec3(-10.0, -8.0, -6.0)), dt, time);
  EXPECT_GT(b.contacts, 50);
  EXPECT_GT(b.work, 10.0 * b.drift);
  return b.error;
}

}  // namespace

// The cell's work closes the energy balance at the integrator's order: frictionless, undamped
// spheres squeezed into contact by the cell, so that the cell's work is most of the energy in
// play; halving the time step divides the balance error by about four (velocity Verlet is second
// order, docs/integrator.md).
TEST(DeformingCell, EnergyBalanceWithTheCellsWorkIsSecondOrder) {
  const double time = 6e-3;
  const double coarse = balance_error_of_compression(4e-6, time);
  const double fine = balance_error_of_compression(2e-6, time);
  if (test::world_rank() == 0) std::printf("balance error: dt 4e-6 %.3e, 2e-6 %.3e\n", coarse, fine);
  EXPECT_LT(coarse, 1e-2);
  EXPECT_GT(coarse / fine, 3.0) << coarse << " at dt, " << fine << " at dt/2";
}

// The cell's stress, summed at every step from the recorded contacts (dem/engine/cell_stress.h),
// is the Love-Weber stress that the grid-stress machinery gives for one grid cell that is the
// cell (its per-grain shares, each pair once from its lower id, in global-id order), less the
// kinetic part of the peculiar velocities; the two sum in different orders, so to round-off.
// Its off-diagonal terms are Weber's as they are: tangential forces make f (x) l asymmetric.
TEST(DeformingCell, CellStressIsTheGridStressOfTheCellLessTheKineticPart) {
  const SceneConfig s = test::compressing_cell_scene(300, Vec3(0.5, -0.4, -0.5));
  const ParticleStore fill = fill_container(s);
  Simulation sim(s, fill, make_open_box(s.container), MPI_COMM_WORLD);
  sim.run(1500);
  const Box box = sim.decomposition().cell().box;
  RegularGrid grid;
  grid.lo = box.lo;
  grid.hi = box.hi;
  const GridStress g = sim.grid_stress(grid);
  const ParticleStore all = sim.gather_sorted_by_id();
  ASSERT_GT(g.internal_contacts[0], 50);
  if (test::world_rank() != 0) return;
  ASSERT_EQ(g.particles[0], static_cast<long>(all.size())) << "a grain outside the cell's grid";
  Mat3 kinetic = Mat3::Zero();
  for (std::size_t i = 0; i < all.size(); ++i) kinetic += all.mass(i) * all.v[i] * all.v[i].transpose();
  const Mat3 expected = g.sigma[static_cast<int>(StressFormula::weber)][0] - kinetic / g.cell_volume;
  const Mat3& sigma = sim.cell_stress();
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 1.0);
  EXPECT_LT((sigma - expected).cwiseAbs().maxCoeff(), 1e-12 * scale) << sigma << "\nexpected\n" << expected;
  EXPECT_GT(std::abs(sigma(0, 2) - sigma(2, 0)), 1e-9 * scale) << "Weber's asymmetry kept";
}
