// Stress, energies and wall forces of a parallel run (docs/stress.md, "Stress in parallel";
// docs/parallel.md): per-cell tensors of a fixed grid bitwise the same on 1-4 ranks and
// equal to the serial grid_stress() on the same state; compute grids (the blocks) adding
// up to the whole container; a contact across a block face external once in each block;
// energies and wall forces rank-independent and equal to the fast summation's on one rank.
#include <gtest/gtest.h>
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "../common/scenes.h"
#include "dem/engine/simulation.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

double max_abs(const Mat3& m) { return m.cwiseAbs().maxCoeff(); }

// Every number of two GridStress equal with ==; returns the count of differing numbers.
long count_differences(const GridStress& a, const GridStress& b) {
  long d = 0;
  for (int f = 0; f < kStressFormulaCount; ++f)
    for (std::size_t c = 0; c < a.sigma[f].size(); ++c)
      for (int e = 0; e < 9; ++e) d += a.sigma[f][c](e / 3, e % 3) != b.sigma[f][c](e / 3, e % 3);
  for (std::size_t c = 0; c < a.particles.size(); ++c) {
    d += a.particles[c] != b.particles[c];
    d += a.internal_contacts[c] != b.internal_contacts[c];
    d += a.external_contacts[c] != b.external_contacts[c];
    d += a.wall_contacts[c] != b.wall_contacts[c];
    d += a.solid_fraction[c] != b.solid_fraction[c];
  }
  return d;
}

RegularGrid grid_3x3x4(const SceneConfig& s, double height) {
  RegularGrid g;
  g.lo = Vec3(0, 0, 0);
  g.hi = Vec3(s.container.lx, s.container.ly, height);
  g.n[0] = 3;
  g.n[1] = 3;
  g.n[2] = 4;
  return g;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A deposition of 600 spheres, mid-way (impacts, first compaction), with the contacts of
// the last step recorded.
struct MidDeposition {
  static constexpr long kSteps = 3000;
  SceneConfig scene = test::deposition_scene(600);
  ParticleStore particles = fill_container(scene);
};

void run_recording(Simulation& sim, long steps) {
  sim.run(steps - 1);
  sim.request_contacts();
  sim.step();
}

}  // namespace

TEST(ParallelStress, FixedGridIsBitwiseRankIndependentAndEqualsSerial) {
  const MidDeposition d;
  // The grid ends inside the falling cloud: grains above it are outside every cell.
  const RegularGrid grid = grid_3x3x4(d.scene, 0.02);
  Simulation world(d.scene, d.particles, MPI_COMM_WORLD);
  run_recording(world, MidDeposition::kSteps);
  ASSERT_TRUE(world.contacts_recorded());
  const GridStress g = world.grid_stress(grid);
  const ParticleStore state = world.gather_sorted_by_id();
  const std::vector<ContactRecord> contacts = world.gather_contacts_by_id();

  // Cost of one evaluation (fixed grid + compute grids) against a step, on this run.
  const int repeats = 20;
  auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < repeats; ++k) {
    const GridStress again = world.grid_stress(grid);
    if (k == 0) {
      EXPECT_EQ(count_differences(g, again), 0);
    }
  }
  const double t_fixed = seconds_since(t0) / repeats;
  t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < repeats; ++k) (void)world.compute_grid_stress();
  const double t_compute = seconds_since(t0) / repeats;
  const auto t1 = std::chrono::steady_clock::now();
  world.run(200);
  const double t_step = seconds_since(t1) / 200;
  const auto t2 = std::chrono::steady_clock::now();
  world.request_contacts();
  world.step();
  const double t_recording_step = seconds_since(t2);

  if (test::world_rank() != 0) return;
  std::printf(
      "stress cost on %d ranks: fixed 3x3x4 grid %.3g ms, compute grids %.3g ms per evaluation; step %.3g "
      "ms (recording step %.3g ms); %zu contacts\n",
      test::world_size(), 1e3 * t_fixed, 1e3 * t_compute, 1e3 * t_step, 1e3 * t_recording_step,
      contacts.size());

  // The same scene on one rank: every number identical.
  Simulation self(d.scene, d.particles, MPI_COMM_SELF);
  run_recording(self, MidDeposition::kSteps);
  const GridStress g1 = self.grid_stress(grid);
  EXPECT_EQ(count_differences(g, g1), 0) << test::world_size() << " ranks vs 1";

  // The serial grid_stress on the gathered state and contacts: equal to round-off (it sums
  // contact by contact, the parallel path grain by grain in id order).
  const GridStress s = grid_stress(state, contacts_in_store(contacts, state), grid, world.grain_dynamics());
  long grains = 0;
  for (int c = 0; c < grid.num_cells(); ++c) {
    grains += g.particles[c];
    EXPECT_EQ(g.particles[c], s.particles[c]) << "cell " << c;
    EXPECT_EQ(g.internal_contacts[c], s.internal_contacts[c]) << "cell " << c;
    EXPECT_EQ(g.external_contacts[c], s.external_contacts[c]) << "cell " << c;
    EXPECT_EQ(g.wall_contacts[c], s.wall_contacts[c]) << "cell " << c;
    EXPECT_NEAR(g.solid_fraction[c], s.solid_fraction[c], 1e-14);
    for (int f = 0; f < kStressFormulaCount; ++f) {
      const double scale = max_abs(s.sigma[f][c]);
      EXPECT_LE(max_abs(g.sigma[f][c] - s.sigma[f][c]), 1e-12 * scale)
          << kStressFormulaNames[f] << ", cell " << c << "\n"
          << g.sigma[f][c] << "\nvs\n"
          << s.sigma[f][c];
    }
  }
  EXPECT_GT(grains, 300);
  EXPECT_LT(grains, 600);  // some still falling above the grid
  // The lower cells are loaded and in contact.
  EXPECT_GT(g.internal_contacts[0], 0);
  EXPECT_LT(g[StressFormula::bagi][0](2, 2), 0.0);
}

TEST(ParallelStress, ComputeGridsAddUpToTheWholeContainer) {
  const MidDeposition d;
  Simulation world(d.scene, d.particles, MPI_COMM_WORLD);
  run_recording(world, MidDeposition::kSteps);
  const ComputeGridStress cg = world.compute_grid_stress();
  const ParticleStore state = world.gather_sorted_by_id();
  const std::vector<ContactRecord> contacts = world.gather_contacts_by_id();
  ASSERT_EQ(static_cast<int>(cg.stress.particles.size()), test::world_size());
  if (test::world_rank() != 0) return;

  RegularGrid whole;  // one cell holding every grain
  whole.lo = Vec3(-1, -1, -1);
  whole.hi = Vec3(1, 1, 1);
  const GridStress all =
      grid_stress(state, contacts_in_store(contacts, state), whole, world.grain_dynamics());
  long grains = 0, walls = 0, external = 0, internal = 0;
  for (int r = 0; r < test::world_size(); ++r) {
    grains += cg.stress.particles[r];
    walls += cg.stress.wall_contacts[r];
    external += cg.stress.external_contacts[r];
    internal += cg.stress.internal_contacts[r];
  }
  EXPECT_EQ(grains, 600);
  EXPECT_EQ(walls, all.wall_contacts[0]);
  // A pair across two blocks is external once in each; all pairs counted exactly once.
  EXPECT_EQ(external % 2, 0);
  EXPECT_EQ(internal + external / 2, all.internal_contacts[0]);
  if (test::world_size() > 1) {
    EXPECT_GT(external, 0);
  }
  for (StressFormula f :
       {StressFormula::bagi, StressFormula::modified_nicot, StressFormula::modified_de_saxce}) {
    Mat3 sum = Mat3::Zero();
    for (int r = 0; r < test::world_size(); ++r) sum += cg.stress.volume[r] * cg.stress[f][r];
    const Mat3 expected = all.cell_volume * all[f][0];
    EXPECT_LE(max_abs(sum - expected), 1e-12 * max_abs(expected)) << name_of(f) << "\n"
                                                                  << sum << "\nvs\n"
                                                                  << expected;
  }
}

// Two spheres pressed together across the face between blocks 0 and 1 (blocks along x):
// each block sees one external contact (force on its own sphere, branch to the contact
// point); on one rank it is one internal contact. The blocks' V sigma add up to the
// internal form f (x) (x_b - x_a).
TEST(ParallelStress, ContactAcrossABlockFaceIsExternalOnceInEachBlock) {
  SceneConfig s = test::bare_scene(1e-6);
  s.effects = {false, true, true, false, true, true};
  s.particles.material = {2650.0, 5e7, 0.25};
  const int k = test::world_size();
  EngineOptions o;
  o.blocks = {k, 1, 1};
  o.box = Box{Vec3(0, 0, 0), Vec3(0.01 * k, 0.01, 0.01)};
  const double face = 0.01, r = 1e-3;
  ParticleStore p;
  p.add_sphere(0, r, 2650, Vec3(face - 0.95e-3, 0.005, 0.005), Vec3(0.1, 0, 0), Vec3::Zero());
  p.add_sphere(1, r, 2650, Vec3(face + 0.95e-3, 0.005, 0.005), Vec3(-0.1, 0, 0), Vec3::Zero());
  Simulation sim(s, p, {}, MPI_COMM_WORLD, o);
  sim.request_contacts();
  sim.step();
  const ComputeGridStress cg = sim.compute_grid_stress();
  const ParticleStore state = sim.gather_sorted_by_id();
  const std::vector<ContactRecord> contacts = sim.gather_contacts_by_id();
  if (test::world_rank() != 0) return;
  ASSERT_EQ(contacts.size(), 1u);
  const Vec3 f = get(contacts[0].force);
  const Vec3 point = get(contacts[0].point);
  EXPECT_GT(-f.x(), 0.0);  // sphere 0 is pushed back
  if (k == 1) {
    EXPECT_EQ(cg.stress.internal_contacts[0], 1);
    EXPECT_EQ(cg.stress.external_contacts[0], 0);
  } else {
    for (int b = 0; b < k; ++b) {
      EXPECT_EQ(cg.stress.internal_contacts[b], 0) << "block " << b;
      EXPECT_EQ(cg.stress.external_contacts[b], b < 2 ? 1 : 0) << "block " << b;
      EXPECT_EQ(cg.stress.particles[b], b < 2 ? 1 : 0) << "block " << b;
    }
    // Block 0 holds sphere 0: Bagi = f (x) (x^c - x^0) / V0, Drescher f (x) x^c / V0.
    const Mat3 bagi0 = f * (point - state.x[0]).transpose() / cg.stress.volume[0];
    EXPECT_LE(max_abs(cg.stress[StressFormula::bagi][0] - bagi0), 1e-15 * max_abs(bagi0));
    const Mat3 bagi1 = -f * (point - state.x[1]).transpose() / cg.stress.volume[1];
    EXPECT_LE(max_abs(cg.stress[StressFormula::bagi][1] - bagi1), 1e-15 * max_abs(bagi1));
    EXPECT_EQ(cg.stress[StressFormula::weber][0], Mat3::Zero());
  }
  Mat3 sum = Mat3::Zero();
  for (int b = 0; b < k; ++b) sum += cg.stress.volume[b] * cg.stress[StressFormula::bagi][b];
  const Mat3 internal = f * (state.x[1] - state.x[0]).transpose();
  EXPECT_LE(max_abs(sum - internal), 1e-14 * max_abs(internal));
  EXPECT_LT(internal(0, 0), 0.0);  // compression
}

namespace {

void expect_energies_close(const EnergyBalance& a, const EnergyBalance& b, double tol,
                           const std::string& what) {
  const double scale =
      std::abs(a.potential) + a.kinetic() + a.elastic_normal + a.dissipated_damping + a.dissipated_friction;
  const double fields[][2] = {{a.kinetic_translational, b.kinetic_translational},
                              {a.kinetic_rotational, b.kinetic_rotational},
                              {a.potential, b.potential},
                              {a.elastic_normal, b.elastic_normal},
                              {a.elastic_tangential, b.elastic_tangential},
                              {a.dissipated_damping, b.dissipated_damping},
                              {a.dissipated_friction, b.dissipated_friction},
                              {a.tangential_stiffness_change, b.tangential_stiffness_change}};
  const char* names[] = {"kinetic translational", "kinetic rotational", "potential",
                         "elastic normal",        "elastic tangential", "dissipated damping",
                         "dissipated friction",   "stiffness change"};
  for (int k = 0; k < 8; ++k) {
    // Each field to tol of itself, and never worse than tol of the whole budget.
    const double bound = tol * std::max(std::abs(fields[k][1]), 1e-3 * scale);
    EXPECT_LE(std::abs(fields[k][0] - fields[k][1]), bound)
        << what << ": " << names[k] << " " << fields[k][0] << " vs " << fields[k][1];
  }
}

}  // namespace

TEST(ParallelEnergy, PatchTestEnergiesAndWallForcesEqualTheFastSummation) {
  const SceneConfig s = test::patch_scene();
  const ParticleStore p = fill_container(s);
  Simulation world(s, p, MPI_COMM_WORLD);
  world.run(300);
  const EnergyBalance e = world.energy();
  const std::vector<Vec3> walls = world.wall_forces();
  if (test::world_rank() != 0) return;
  Simulation fast(s, p, MPI_COMM_SELF, test::fast_summation());
  fast.run(300);
  const EnergyBalance es = fast.energy();
  EXPECT_GT(es.elastic_normal, 0.0);
  EXPECT_GT(es.dissipated_damping, 0.0);
  EXPECT_GT(es.dissipated_friction, 0.0);
  expect_energies_close(e, es, 1e-12, "patch test vs Simulation");
  const std::vector<Vec3>& ws = fast.wall_forces();
  ASSERT_EQ(walls.size(), ws.size());
  double scale = 0.0;
  for (const Vec3& w : ws) scale = std::max(scale, w.cwiseAbs().maxCoeff());
  EXPECT_GT(scale, 0.0);
  for (std::size_t w = 0; w < ws.size(); ++w)
    EXPECT_LE((walls[w] - ws[w]).cwiseAbs().maxCoeff(), 1e-12 * scale) << "wall " << w;
}

TEST(ParallelEnergy, EnergiesAndWallForcesAreRankIndependent) {
  const MidDeposition d;
  Simulation world(d.scene, d.particles, MPI_COMM_WORLD);
  world.run(MidDeposition::kSteps);
  const EnergyBalance e = world.energy();
  const std::vector<Vec3> walls = world.wall_forces();
  // Every rank receives the same numbers.
  double mine[2] = {e.potential, walls[0].z()}, lo[2], hi[2];
  MPI_Allreduce(mine, lo, 2, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(mine, hi, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(lo[0], hi[0]);
  EXPECT_EQ(lo[1], hi[1]);
  if (test::world_rank() != 0) return;
  Simulation self(d.scene, d.particles, MPI_COMM_SELF);
  self.run(MidDeposition::kSteps);
  const EnergyBalance e1 = self.energy();
  const std::vector<Vec3> walls1 = self.wall_forces();
  // Sums over particles in id order: bitwise.
  EXPECT_EQ(e.kinetic_translational, e1.kinetic_translational);
  EXPECT_EQ(e.kinetic_rotational, e1.kinetic_rotational);
  EXPECT_EQ(e.potential, e1.potential);
  EXPECT_EQ(e.elastic_normal, e1.elastic_normal);
  EXPECT_EQ(e.elastic_tangential, e1.elastic_tangential);
  for (std::size_t w = 0; w < walls.size(); ++w) EXPECT_EQ(walls[w], walls1[w]) << "wall " << w;
  expect_energies_close(e, e1, 1e-13, std::to_string(test::world_size()) + " ranks vs 1");
  // Cumulative dissipation: exact sums of each grain's share of each step
  // (dem/parallel/exact_sum.h), so bitwise too.
  EXPECT_EQ(e.dissipated_damping, e1.dissipated_damping);
  EXPECT_EQ(e.dissipated_friction, e1.dissipated_friction);
  EXPECT_EQ(e.tangential_stiffness_change, e1.tangential_stiffness_change);
  std::printf("dissipation on %d ranks vs 1: damping %.3g, friction %.3g relative\n", test::world_size(),
              std::abs(e.dissipated_damping / e1.dissipated_damping - 1.0),
              std::abs(e.dissipated_friction / e1.dissipated_friction - 1.0));
}
