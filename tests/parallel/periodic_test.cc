// Periodic cells on any number of ranks (docs/periodic.md): with the deterministic summation the
// states (positions, velocities, spins, image counters) are bitwise those of one rank, which is
// its own neighbour across every periodic face; with two blocks along a periodic axis both
// neighbours are one rank. Grains cross the faces during the runs, with their contacts.
#include <gtest/gtest.h>
#include <mpi.h>

#include <random>

#include "dem/boundary/container.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// How many grains of a gathered state have crossed a face (rank 0).
long crossed(const ParticleStore& p) {
  long n = 0;
  for (const ImageCount& c : p.image) n += (c[0] != 0 || c[1] != 0 || c[2] != 0) ? 1 : 0;
  return n;
}

}  // namespace

// A deposition over a floor without side walls: periodic x and y, grains thrown sideways.
TEST(Periodic, BedWithoutSideWallsIsBitwiseIdenticalOnAnyRankCount) {
  SceneConfig s = test::deposition_scene(300);
  s.container.periodic = {true, true, false};
  s.fill.velocity = Vec3(0.5, -0.4, -0.5);
  const ParticleStore fill = fill_container(s);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  ASSERT_EQ(walls.size(), 1u);  // the floor alone
  test::expect_rank_independent(s, fill, walls, {}, {}, 1500);
  Simulation sim(s, fill, walls, MPI_COMM_WORLD);
  sim.run(1500);
  const ParticleStore all = sim.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    EXPECT_GT(crossed(all), 50) << "grains crossed the periodic faces";
  }
}

// A spinning cube of touching spheres across the corner of a fully periodic cell, drifting
// diagonally: contacts across faces, edges and corners, with tangential springs, through wraps
// and migrations.
TEST(Periodic, SpinningCubeAcrossTheCornerOfAFullyPeriodicCellIsBitwiseIdentical) {
  SceneConfig s;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = s.container.height = 0.024;
  s.container.periodic = {true, true, true};
  s.effects.gravity = false;
  s.friction = 0.5;
  s.damping_ratio = 0.3;
  s.time_step = 1e-5;
  std::mt19937_64 rng(7);
  ParticleStore p;
  const double r = 1.5e-3;
  test::add_touching_cube(p, 4, r, Vec3(-0.004, -0.0035, -0.003), Vec3(0.6, 0.45, -0.35), rng);
  test::expect_rank_independent(s, p, {}, {}, {}, 800);
  Simulation sim(s, p, std::vector<PlaneWall>{}, MPI_COMM_WORLD);
  EXPECT_GT(sim.diagnostics().particle_contacts, 100) << "the cube's contacts across the faces";
  sim.run(800);
  const ParticleStore all = sim.gather_sorted_by_id();
  if (test::world_rank() == 0) {
    EXPECT_GT(crossed(all), 30);
  }
}

// The fast summation returns the images' shares along the same routes (one rank: to itself):
// the same motion as the deterministic order to round-off.
TEST(Periodic, FastSummationAgreesToRoundOff) {
  SceneConfig s = test::deposition_scene(200);
  s.container.periodic = {true, true, false};
  s.fill.velocity = Vec3(0.5, -0.4, -0.5);
  const ParticleStore fill = fill_container(s);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  Simulation fast(s, fill, walls, MPI_COMM_WORLD, test::fast_summation());
  Simulation deterministic(s, fill, walls, MPI_COMM_WORLD);
  // Few steps: the impacts of a deposition amplify round-off.
  fast.run(300);
  deterministic.run(300);
  const ParticleStore a = fast.gather_sorted_by_id(), b = deterministic.gather_sorted_by_id();
  if (test::world_rank() != 0) return;
  ASSERT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.image[i], b.image[i]);
    worst = std::max(worst, (a.x[i] - b.x[i]).norm());
  }
  EXPECT_LT(worst, 1e-9);
}
