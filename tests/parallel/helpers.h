#pragma once
// Shared pieces of the parallel tests: scenes, and the bitwise comparison of a run on all
// ranks of MPI_COMM_WORLD with the same run on rank 0 alone (MPI_COMM_SELF).
#include <gtest/gtest.h>
#include <mpi.h>

#include <random>
#include <sstream>
#include <string>

#include "../common/world.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"

namespace upgrain::test {

// The engine on one rank with the fast summation: the serial loop of LAMMPS's `newton on`, the
// reference the deterministic summation is compared with to round-off.
inline dem::EngineOptions fast_summation() {
  dem::EngineOptions o;
  o.summation = dem::Summation::fast;
  return o;
}

// Bitwise equality of x, v and omega, the periodic image counters, and of the orientations when the stores
// have shapes, particle by particle (both sorted by id). Reports the count of differing numbers and the first
// difference, not one failure per number.
inline void expect_bitwise_equal(const dem::ParticleStore& a, const dem::ParticleStore& b,
                                 const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  ASSERT_EQ(a.has_shapes(), b.has_shapes()) << what;
  long differing = 0;
  std::string first;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.id[i], b.id[i]) << what;
    for (int d = 0; d < 3; ++d) {
      const double pairs[3][2] = {
          {a.x[i][d], b.x[i][d]}, {a.v[i][d], b.v[i][d]}, {a.omega[i][d], b.omega[i][d]}};
      for (int f = 0; f < 3; ++f) {
        if (pairs[f][0] == pairs[f][1]) continue;
        if (differing++ == 0) {
          std::ostringstream m;
          m.precision(17);
          m << "particle " << a.id[i] << " "
            << "xvw"[f] << "[" << d << "]: " << pairs[f][0] << " vs " << pairs[f][1];
          first = m.str();
        }
      }
    }
    if (a.image[i] != b.image[i] && differing++ == 0)
      first = "particle " + std::to_string(a.id[i]) + " image counter";
    if (!a.has_shapes()) continue;
    ASSERT_EQ(a.semi_axes[i], b.semi_axes[i]) << what;
    for (int c = 0; c < 4; ++c) {
      if (a.orientation[i].coeffs()[c] == b.orientation[i].coeffs()[c]) continue;
      if (differing++ == 0) {
        std::ostringstream m;
        m.precision(17);
        m << "particle " << a.id[i] << " orientation coefficient " << c << ": "
          << a.orientation[i].coeffs()[c] << " vs " << b.orientation[i].coeffs()[c];
        first = m.str();
      }
    }
  }
  EXPECT_EQ(differing, 0) << what << ": first difference " << first;
}

// Runs `steps` steps on MPI_COMM_WORLD and, on rank 0, the same scene on MPI_COMM_SELF,
// and compares the states bitwise. Returns the world run's diagnostics (this rank).
inline dem::RankDiagnostics expect_rank_independent(const dem::SceneConfig& scene,
                                                    const dem::ParticleStore& particles,
                                                    const std::vector<dem::PlaneWall>& walls,
                                                    const dem::EngineOptions& world_options,
                                                    const dem::EngineOptions& self_options, long steps) {
  dem::Simulation world(scene, particles, walls, MPI_COMM_WORLD, world_options);
  world.run(steps);
  const dem::ParticleStore parallel = world.gather_sorted_by_id();
  if (world_rank() == 0) {
    dem::Simulation self(scene, particles, walls, MPI_COMM_SELF, self_options);
    self.run(steps);
    const dem::ParticleStore serial = self.gather_sorted_by_id();
    EXPECT_EQ(parallel.size(), particles.size());
    expect_bitwise_equal(parallel, serial, std::to_string(world_size()) + " ranks vs 1");
  }
  return world.rank_diagnostics();
}

// Yan and Regueiro's patch test scene (docs/stress.md): 162 spheres, two layers of 9 x 9, dropped with some
// random velocity into an open box so that they hit the floor and each other.
inline dem::SceneConfig patch_scene() {
  dem::SceneConfig s;
  s.particles.count = 162;
  s.particles.radius = 5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  // Lattice pitch 1.1 d = 11 mm; 9 per row needs 8.5 pitches + d + gap.
  s.container.lx = s.container.ly = 0.1045;
  s.fill.bottom_gap = 0.5e-3;
  s.fill.position_jitter = 0.5;
  s.fill.velocity = dem::Vec3(0, 0, -0.5);
  s.fill.velocity_jitter = 0.3;
  s.friction = 0.5;
  s.damping_ratio = 0.3;
  s.time_step = 2e-5;
  return s;
}

// A cube of n^3 spheres whose neighbours touch (slight overlap), spinning, so contacts with
// tangential springs travel with the particles across blocks.
inline void add_touching_cube(dem::ParticleStore& p, int n, double r, const dem::Vec3& corner,
                              const dem::Vec3& v, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double pitch = 2.0 * r * 0.999;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) {
        const dem::Vec3 x = corner + pitch * dem::Vec3(a, b, c);
        p.add_sphere(static_cast<dem::GlobalId>(p.size()), r, 2650, x,
                     v + 0.05 * dem::Vec3(u(rng), u(rng), u(rng)), 200.0 * dem::Vec3(u(rng), u(rng), u(rng)));
      }
}

// A smaller cousin of tests/regression/deposition_test.cc's scene.
inline dem::SceneConfig deposition_scene(long count) {
  dem::SceneConfig s;
  s.particles.count = count;
  s.particles.radius = 1.5e-3;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = 0.03;
  s.fill.bottom_gap = 0.002;
  s.fill.position_jitter = 0.5;
  s.fill.velocity = dem::Vec3(0, 0, -0.5);
  s.fill.velocity_jitter = 0.2;
  s.friction = 0.5;
  s.damping_ratio = 0.7;
  s.time_step = 1e-5;
  return s;
}

// deposition_scene() in a cell periodic along x and y that deforms (docs/periodic.md, "A cell
// that deforms"): squeezed along x at -3 /s, and along y by a servo to a lateral pressure of
// 150 Pa (kinetic part included), its rate set from the cell's stress every step.
inline dem::SceneConfig compressing_cell_scene(long count, const dem::Vec3& throw_velocity) {
  dem::SceneConfig s = deposition_scene(count);
  s.container.periodic = {true, true, false};
  s.fill.velocity = throw_velocity;
  s.cell.axis[0] = {dem::CellAxisMode::rate, -3.0};
  s.cell.axis[1] = {dem::CellAxisMode::servo, 0.0, 150.0, 0.01, 2.0};
  return s;
}

// A fully periodic cube of side `side`, no gravity, the given rates on the diagonal of L
// (docs/periodic.md, "A cell that deforms").
inline dem::SceneConfig gas_cell(double side, const dem::Vec3& rates) {
  dem::SceneConfig s;
  s.particles.material = {2650.0, 5e7, 0.25};
  s.container.lx = s.container.ly = s.container.height = side;
  s.container.periodic = {true, true, true};
  s.effects.gravity = false;
  s.friction = 0.5;
  s.damping_ratio = 0.3;
  s.time_step = 1e-5;
  for (int d = 0; d < 3; ++d) {
    if (rates[d] == 0.0) continue;
    s.cell.axis[d].mode = dem::CellAxisMode::rate;
    s.cell.axis[d].rate = rates[d];
  }
  return s;
}

// n^3 grains on a lattice of pitch side / n, moved by up to `jitter` pitches, their peculiar
// velocities zero or random, up to `speed`.
inline dem::ParticleStore lattice(int n, double side, double r, double speed, std::mt19937_64& rng,
                                  double jitter = 0.05) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  dem::ParticleStore p;
  const double pitch = side / n;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c) {
        const dem::Vec3 x = pitch * (dem::Vec3(a, b, c) + dem::Vec3::Constant(0.5)) +
                            jitter * pitch * dem::Vec3(u(rng), u(rng), u(rng));
        p.add_sphere(static_cast<dem::GlobalId>(p.size()), r, 2650, x,
                     speed * dem::Vec3(u(rng), u(rng), u(rng)), dem::Vec3::Zero());
      }
  return p;
}

// The energy balance of a deforming cell's test (docs/periodic.md, "A cell that deforms"): 125
// frictionless, undamped elastic spheres on a jittered lattice of the cell of side 15 mm that
// `s` moves, with peculiar velocities, run for `time` at time step dt.
struct CellBalance {
  double error = 0.0;  // |balance error|
  double work = 0.0;   // the cell's work
  double drift = 0.0;  // |total - total(0)|
  long contacts = 0;   // at the end
};
inline CellBalance cell_balance(dem::SceneConfig s, double dt, double time) {
  s.friction = 0.0;
  s.damping_ratio = 0.0;
  s.time_step = dt;
  std::mt19937_64 rng(9);
  const dem::ParticleStore p0 = lattice(5, 0.015, 1.45e-3, 0.05, rng, 0.01);
  dem::Simulation sim(s, p0, std::vector<dem::PlaneWall>{}, MPI_COMM_WORLD);
  sim.run(std::lround(time / dt));
  const dem::EnergyBalance e = sim.energy();
  return {std::abs(sim.energy_balance_error()), e.work_by_cell,
          std::abs(e.total() - sim.initial_energy().total()), sim.diagnostics().particle_contacts};
}

}  // namespace upgrain::test
