// The two summations of the engine (docs/architecture.md, "Two summations"):
//  - rolling and twisting resistance, like every effect, are bitwise rank-independent with
//    deterministic summation;
//  - the fast summation (ghost forces returned to their owners) gives on K ranks the states of
//    one rank to round-off, energies and wall forces included;
//  - fast and deterministic simulate the same physics: the bed a deposition leaves has the
//    same invariants within the spread that round-off alone drives.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "coupling/run/scene_run.h"
#include "dem/analysis/bed_state.h"
#include "dem/engine/simulation.h"
#include "helpers.h"
#include "tests/common/relaxed_bed.h"

using namespace upgrain;
using namespace upgrain::dem;
using upgrain::coupling::run_scene;
using upgrain::coupling::RunControl;
using upgrain::coupling::RunResult;

namespace {

SceneConfig rolling_scene(long count) {
  SceneConfig s = test::deposition_scene(count);
  s.effects.rolling_resistance = true;
  s.effects.twisting_resistance = true;
  s.rolling_friction = 0.1;
  s.rolling_damping_ratio = 0.3;
  return s;
}

// Yan and Regueiro's mix of shapes (as tests/parallel/ellipsoid_test.cc), with rolling resistance.
SceneConfig rolling_ellipsoid_scene(long count) {
  SceneConfig s = test::paper_ellipsoid_bed_scene(count);
  s.container.lx = s.container.ly = 0.04;
  s.fill.velocity = Vec3(0, 0, -1.0);
  s.fill.velocity_jitter = 0.5;
  s.effects.rolling_resistance = true;
  s.rolling_friction = 0.1;
  s.rolling_damping_ratio = 0.3;
  return s;
}

double max_relative_difference(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, (a[i] - b[i]).cwiseAbs().maxCoeff());
    scale = std::max(scale, a[i].cwiseAbs().maxCoeff());
  }
  return scale > 0.0 ? diff / scale : diff;
}

// Runs `steps` steps, recording the contacts every `every` steps, and returns the pairs across
// two ranks evaluated on one of them, summed over the samples and the ranks.
long run_counting_contacts_across_ranks(Simulation& world, int steps, int every) {
  long across = 0;
  for (int done = 0; done < steps; done += every) {
    world.run(every - 1);
    world.request_contacts();
    world.run(1);
    for (const ContactSample& c : world.contacts()) across += !c.with_wall() && c.b >= world.owned() ? 1 : 0;
  }
  MPI_Allreduce(MPI_IN_PLACE, &across, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return across;
}

}  // namespace

TEST(Summation, RollingResistanceIsBitwiseRankIndependent) {
  const SceneConfig s = rolling_scene(600);
  const ParticleStore p = fill_container(s);
  test::expect_rank_independent(s, p, make_open_box(s.container), {}, {}, 3000);
  // The rolling springs' energy is summed per particle in global-id order: bitwise too.
  Simulation world(s, p, MPI_COMM_WORLD);
  world.run(1500);
  const EnergyBalance e = world.energy();
  EXPECT_GT(e.elastic_rolling, 0.0);
  if (test::world_rank() == 0) {
    Simulation self(s, p, MPI_COMM_SELF);
    self.run(1500);
    const EnergyBalance o = self.energy();
    EXPECT_EQ(e.elastic_rolling, o.elastic_rolling);
    EXPECT_EQ(e.elastic_normal, o.elastic_normal);
    EXPECT_EQ(e.kinetic_rotational, o.kinetic_rotational);
    EXPECT_NEAR(e.dissipated_rolling, o.dissipated_rolling, 1e-12 * std::abs(o.dissipated_rolling));
    // Exact sums of each grain's share of each step (dem/parallel/exact_sum.h): bitwise.
    EXPECT_EQ(e.dissipated_rolling, o.dissipated_rolling);
    EXPECT_EQ(e.rolling_stiffness_change, o.rolling_stiffness_change);
    EXPECT_EQ(e.dissipated_damping, o.dissipated_damping);
  }
}

TEST(Summation, RollingResistanceOnEllipsoidsIsBitwiseRankIndependent) {
  const SceneConfig s = rolling_ellipsoid_scene(150);
  const ParticleStore p = fill_container(s);
  ASSERT_TRUE(p.has_shapes());
  test::expect_rank_independent(s, p, make_open_box(s.container), {}, {}, 4000);
  // The run reached the contacts: grains on the floor and on each other, turning.
  Simulation world(s, p, MPI_COMM_WORLD);
  world.run(4000);
  const StepDiagnostics d = world.diagnostics();
  EXPECT_GT(d.particle_contacts, 0);
  EXPECT_GT(d.wall_contacts, 0);
  EXPECT_GT(world.energy().elastic_rolling, 0.0);
}

// The fast summation evaluates a pair across two ranks once, on one of its owners,
// and sends the ghost's share back: on K ranks the forces are those of one rank summed in
// another order. 600 steps of the patch test (first impacts) keep the round-off below 1e-12.
TEST(Summation, FastOnManyRanksMatchesFastOnOneToRoundOff) {
  SceneConfig s = test::patch_scene();
  s.effects.rolling_resistance = true;  // the rolling dashpot's torque travels back too
  const ParticleStore p = fill_container(s);
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  Simulation world(s, p, walls, MPI_COMM_WORLD, test::fast_summation());
  // Pairs across two ranks, evaluated on one of them: their shares went back to the other.
  const long across = run_counting_contacts_across_ranks(world, 600, 600);
  if (test::world_size() > 1) {
    EXPECT_GT(across, 0);
  }
  const ParticleStore a = world.gather_sorted_by_id();
  const EnergyBalance ea = world.energy();
  const std::vector<Vec3> wa = world.wall_forces();
  const StepDiagnostics da = world.diagnostics();
  if (test::world_rank() != 0) return;
  Simulation self(s, p, walls, MPI_COMM_SELF, test::fast_summation());
  self.run(600);
  const ParticleStore b = self.gather_sorted_by_id();
  const EnergyBalance eb = self.energy();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_LE(max_relative_difference(a.x, b.x), 1e-12);
  EXPECT_LE(max_relative_difference(a.v, b.v), 1e-12);
  EXPECT_LE(max_relative_difference(a.omega, b.omega), 1e-12);
  EXPECT_LE(max_relative_difference(wa, self.wall_forces()), 1e-12);
  EXPECT_NEAR(ea.kinetic(), eb.kinetic(), 1e-12 * eb.kinetic());
  EXPECT_NEAR(ea.elastic_normal, eb.elastic_normal, 1e-9 * eb.elastic_normal);
  EXPECT_NEAR(ea.dissipated_damping, eb.dissipated_damping, 1e-12 * eb.dissipated_damping);
  EXPECT_NEAR(ea.dissipated_rolling, eb.dissipated_rolling, 1e-9 * eb.dissipated_rolling);
  // Every pair once over the ranks.
  EXPECT_EQ(da.particle_contacts, self.diagnostics().particle_contacts);
  EXPECT_EQ(da.wall_contacts, self.diagnostics().wall_contacts);
  std::printf(
      "fast on %d ranks vs 1 (%ld contacts across ranks): x %.2g, v %.2g, omega %.2g of their scales\n",
      test::world_size(), across, max_relative_difference(a.x, b.x), max_relative_difference(a.v, b.v),
      max_relative_difference(a.omega, b.omega));
}

// The same with spheres and ellipsoids (Yan and Regueiro's 1:0.8:0.6) mixed: the shaped pairs'
// levers, torques and viscous torques go back with the ghosts' shares too. The grains' impacts
// amplify the round-off of the other summation order (as OneRankMatchesTheFastSummation in
// ellipsoid_test.cc: to 1e-10 of the fields' scales).
TEST(Summation, FastEllipsoidsOnManyRanksMatchFastOnOneToRoundOff) {
  SceneConfig s = test::patch_scene();
  s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(1.0, 0.8, 0.6)};
  const ParticleStore p = fill_container(s);
  ASSERT_TRUE(p.has_shapes());
  constexpr int kSteps = 1000;
  const std::vector<PlaneWall> walls = make_open_box(s.container);
  Simulation world(s, p, walls, MPI_COMM_WORLD, test::fast_summation());
  // Pairs across two ranks, counted every 250 steps of the run.
  const long across = run_counting_contacts_across_ranks(world, kSteps, 250);
  if (test::world_size() > 1) {
    EXPECT_GT(across, 0);
  }
  const ParticleStore a = world.gather_sorted_by_id();
  const EnergyBalance ea = world.energy();
  if (test::world_rank() != 0) return;
  Simulation self(s, p, walls, MPI_COMM_SELF, test::fast_summation());
  self.run(kSteps);
  const ParticleStore b = self.gather_sorted_by_id();
  const EnergyBalance eb = self.energy();
  ASSERT_EQ(a.size(), b.size());
  std::vector<Vec3> qa, qb;  // the orientations' vector parts
  for (std::size_t i = 0; i < a.size(); ++i) {
    qa.push_back(a.orientation[i].vec());
    qb.push_back(b.orientation[i].vec());
  }
  EXPECT_LE(max_relative_difference(a.x, b.x), 1e-10);
  EXPECT_LE(max_relative_difference(a.v, b.v), 1e-10);
  EXPECT_LE(max_relative_difference(a.omega, b.omega), 1e-10);
  EXPECT_LE(max_relative_difference(qa, qb), 1e-10);
  EXPECT_NEAR(ea.kinetic(), eb.kinetic(), 1e-9 * eb.kinetic());
  EXPECT_NEAR(ea.dissipated_damping, eb.dissipated_damping, 1e-9 * eb.dissipated_damping);
  EXPECT_GT(eb.dissipated_damping, 0.0);
  std::printf(
      "fast ellipsoids on %d ranks vs 1 (%ld contacts across ranks): x %.2g, v %.2g, omega %.2g, q %.2g\n",
      test::world_size(), across, max_relative_difference(a.x, b.x), max_relative_difference(a.v, b.v),
      max_relative_difference(a.omega, b.omega), max_relative_difference(qa, qb));
}

namespace {

// What a user reads off a bed at rest.
struct BedInvariants {
  double height = 0.0;
  double solid_fraction = 0.0;
  double contacts_per_particle = 0.0;
  double floor_share = 0.0;  // share of the weight carried by the floor
};

BedInvariants settle(Simulation& sim, const SceneConfig& s) {
  RunControl control;
  control.rest_ratio = 1e-6;
  const RunResult r = run_scene(sim, control, std::nullopt);
  BedInvariants b;
  if (sim.is_root()) {
    b.height = r.bed.surface_height;
    b.solid_fraction = r.bed.solid_fraction;
  }
  b.contacts_per_particle = 2.0 * static_cast<double>(r.diagnostics.particle_contacts) / sim.particle_count();
  MPI_Bcast(&b.height, 1, MPI_DOUBLE, 0, sim.comm());
  MPI_Bcast(&b.solid_fraction, 1, MPI_DOUBLE, 0, sim.comm());
  double mass = r.total_mass;
  MPI_Bcast(&mass, 1, MPI_DOUBLE, 0, sim.comm());
  b.floor_share = -r.wall_forces[0].z() / (mass * s.gravity);
  return b;
}

}  // namespace

// A deposition is chaotic: the last bits of a sum, amplified by every impact, end in another
// packing. Deterministic runs whose initial positions differ by a few ulps show the spread
// round-off drives in what a user reads off the bed; the fast summation, on one rank and on
// all, must give a bed inside that spread (mean +- 4 standard deviations of the ensemble). The
// ensemble's members run side by side, one rank each.
TEST(Summation, FastAndDeterministicBedsAgreeWithinTheRoundOffSpread) {
  SceneConfig s = test::deposition_scene(160);
  s.end_time = 1.0;  // an upper bound: the runs stop at rest
  const ParticleStore p = fill_container(s);
  Simulation fast_world(s, p, MPI_COMM_WORLD, test::fast_summation());
  const BedInvariants fast_all = settle(fast_world, s);
  const int members = std::max(6, test::world_size());
  std::vector<BedInvariants> ensemble(static_cast<std::size_t>(members));
  for (int k = test::world_rank(); k < members; k += test::world_size()) {
    ParticleStore q = p;
    // k ulps on every coordinate of every grain.
    for (Vec3& x : q.x)
      for (int d = 0; d < 3; ++d)
        for (int u = 0; u < k; ++u) x[d] = std::nextafter(x[d], std::numeric_limits<double>::infinity());
    Simulation det(s, q, MPI_COMM_SELF);
    ensemble[static_cast<std::size_t>(k)] = settle(det, s);
  }
  // Each member from the rank that ran it (the others hold zeros).
  static_assert(sizeof(BedInvariants) == 4 * sizeof(double));
  MPI_Allreduce(MPI_IN_PLACE, ensemble.data(), 4 * members, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  if (test::world_rank() != 0) return;
  Simulation fast_one(s, p, MPI_COMM_SELF, test::fast_summation());
  const BedInvariants fast_single = settle(fast_one, s);
  auto band = [&](double BedInvariants::*f, const char* name) {
    double mean = 0.0, var = 0.0;
    for (const BedInvariants& b : ensemble) mean += b.*f;
    mean /= static_cast<double>(ensemble.size());
    for (const BedInvariants& b : ensemble) var += (b.*f - mean) * (b.*f - mean);
    const double sigma = std::sqrt(var / static_cast<double>(ensemble.size() - 1));
    std::printf("%s: deterministic %.6g +- %.3g (sigma, %zu runs), fast on 1 rank %.6g, on %d ranks %.6g\n",
                name, mean, sigma, ensemble.size(), fast_single.*f, test::world_size(), fast_all.*f);
    EXPECT_GT(sigma, 0.0) << name << ": round-off drove no spread, the ensemble tests nothing";
    EXPECT_NEAR(fast_single.*f, mean, 4.0 * sigma) << name;
    EXPECT_NEAR(fast_all.*f, mean, 4.0 * sigma) << name;
  };
  band(&BedInvariants::height, "bed height (m)");
  band(&BedInvariants::solid_fraction, "solid fraction");
  band(&BedInvariants::contacts_per_particle, "contacts per particle");
  band(&BedInvariants::floor_share, "floor share of the weight");
}
