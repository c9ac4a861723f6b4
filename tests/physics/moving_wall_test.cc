// Walls that translate (PlaneWall::velocity, docs/scenes.md "Moving walls"), against answers
// from rigid-body mechanics:
//  - a sphere dropped onto a belt moving at v_w (the floor moving in its own plane) slides,
//    then rolls without slip at v = 2/7 v_w; the belt's work is m v v_w = 2/7 m v_w^2, of which
//    1/7 m v_w^2 stays as kinetic energy and 1/7 m v_w^2 is dissipated by friction;
//  - a lid pressed onto a sphere on the floor at a steady speed and then stopped: the work the
//    lid did equals the elastic energy stored plus the damping dissipated, and at rest the two
//    contacts carry the Hertz force of the same overlap;
//  - a lid starting many skins away reaches the sphere: the lists follow a moving wall;
//  - a wall added between two steps (to a running or a restored engine, either summation)
//    carries no load until the next step, and the others keep theirs.
#include <gtest/gtest.h>

#include <cmath>

#include "../common/scenes.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/law/hertz.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

constexpr double kR = 5e-3;
constexpr double kRho = 2650.0;

double sphere_mass() { return kRho * 4.0 / 3.0 * M_PI * kR * kR * kR; }

}  // namespace

TEST(MovingWall, BeltBringsASphereToTwoSeventhsOfItsSpeed) {
  SceneConfig s = test::bare_scene(2e-6);
  s.effects.gravity = true;
  s.effects.wall_friction = true;
  s.effects.rotation = true;
  s.effects.energy_tracking = true;
  s.container.lx = s.container.ly = 10.0;
  const double mu = 0.3, v_w = 0.2, g = 9.81, m = sphere_mass();
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  const double delta = hertz::overlap_for_force(cm.e_star, kR, m * g);
  ParticleStore p;
  p.add_sphere(0, kR, kRho, Vec3(1.0, 5.0, kR - delta), Vec3::Zero(), Vec3::Zero());
  PlaneWall belt{"belt", Vec3::Zero(), Vec3(0, 0, 1), mu};
  belt.velocity = Vec3(v_w, 0, 0);
  Simulation sim(s, p, {belt});
  const EnergyBalance e0 = sim.energy();
  // Slip ends at t = 2 v_w / (7 mu g) = 19.4 ms. The undamped tangential spring then rings
  // about the rolling state (its period is a fraction of a millisecond) and touches the
  // Coulomb limit now and then, slipping a little: the figures are means over the 30 ms after
  // 30 ms, within 1e-3 of the rigid bodies' answer (measured: 6e-4).
  const long settle = static_cast<long>(0.03 / s.time_step);
  sim.run(settle);
  const double friction_at_settle = sim.energy().dissipated_friction;
  double v_mean = 0, slip_mean = 0;
  for (long k = 0; k < settle; ++k) {
    sim.step();
    const Vec3 v = sim.particles().v[0];
    v_mean += v.x() / settle;
    slip_mean += (v.x() - sim.particles().omega[0].y() * kR - v_w) / settle;
  }
  EXPECT_NEAR(v_mean, 2.0 / 7.0 * v_w, 1e-3 * 2.0 / 7.0 * v_w);
  EXPECT_NEAR(slip_mean, 0.0, 1e-3 * v_w) << "rolls on the belt without slip";
  const EnergyBalance e = sim.energy();
  const double unit = m * v_w * v_w;
  // The belt's work is v_w times the momentum it gave; the sliding phase dissipated the rest.
  EXPECT_NEAR(e.work_by_walls - e0.work_by_walls, v_w * m * sim.particles().v[0].x(), 1e-9 * unit);
  EXPECT_NEAR(e.dissipated_friction, 1.0 / 7.0 * unit, 1e-3 * unit);
  EXPECT_NEAR(e.dissipated_friction, friction_at_settle, 1e-3 * unit) << "hardly any slip once rolling";
  EXPECT_LT(std::abs(balance_error(e0, e)), 1e-5);
  // The belt has carried the wall's point along its plane: the contact does not care.
  EXPECT_NEAR(sim.walls()[0].point.x(), v_w * 2 * settle * s.time_step, 1e-12);
  std::printf("belt: mean v %.7f (2/7 v_w %.7f), friction %.6e J (m v_w^2 / 7 %.6e J), balance error %.2e\n",
              v_mean, 2.0 / 7.0 * v_w, e.dissipated_friction, unit / 7, balance_error(e0, e));
}

TEST(MovingWall, PressedLidWorkIsStoredAndDissipated) {
  SceneConfig s = test::bare_scene(1e-6);
  s.effects.damping = true;
  s.effects.energy_tracking = true;
  s.damping_ratio = 0.5;
  s.container.lx = s.container.ly = 1.0;
  ParticleStore p;
  p.add_sphere(0, kR, kRho, Vec3(0.5, 0.5, kR), Vec3::Zero(), Vec3::Zero());
  PlaneWall floor{"floor", Vec3::Zero(), Vec3(0, 0, 1), 0.0};
  PlaneWall lid{"lid", Vec3(0, 0, 2 * kR), Vec3(0, 0, -1), 0.0};
  const double speed = 0.01;
  lid.velocity = Vec3(0, 0, -speed);
  Simulation sim(s, p, {floor, lid});
  const EnergyBalance e0 = sim.energy();
  const long press = 2000;  // 20 um of travel: a 1e-3 r total squeeze
  sim.run(press);
  const EnergyBalance pressed = sim.energy();
  EXPECT_GT(pressed.dissipated_damping, 0.0) << "the dashpot sees the lid's speed";
  std::printf("lid pressing: balance error %.2e\n", balance_error(e0, pressed));
  sim.set_wall_velocity(sim.wall_index("lid"), Vec3::Zero());
  sim.run(200000);
  const EnergyBalance e = sim.energy();
  const double travel = speed * press * s.time_step;
  EXPECT_NEAR(2 * kR - sim.walls()[1].point.z(), travel, 1e-12);
  // The squeeze is shared by the two contacts, which carry the same force at rest.
  const double overlap = 0.5 * travel;
  const HertzNormal::Constants cm = HertzNormal::constants(s.particles.material, {}).pair;
  const double force = hertz::normal_force(cm.e_star, kR, overlap);
  const std::vector<Vec3> f = sim.wall_forces();
  EXPECT_NEAR(f[0].z(), -force, 1e-6 * force);
  EXPECT_NEAR(f[1].z(), force, 1e-6 * force);
  // Work in = elastic energy of two contacts + dashpot dissipation (+ what kinetic is left).
  const double stored = 2 * hertz::normal_energy(cm.e_star, kR, overlap);
  EXPECT_NEAR(e.elastic_normal, stored, 1e-5 * stored);
  EXPECT_NEAR(e.work_by_walls, e.elastic_normal + e.dissipated_damping + e.kinetic(), 1e-6 * e.work_by_walls);
  EXPECT_LT(std::abs(balance_error(e0, e)), 1e-6);
  std::printf("lid: work %.6e J, elastic %.6e J, damping %.6e J, balance error %.2e\n", e.work_by_walls,
              e.elastic_normal, e.dissipated_damping, balance_error(e0, e));
}

TEST(MovingWall, ListsFollowTheWall) {
  SceneConfig s = test::bare_scene(1e-6);
  s.effects.energy_tracking = true;
  s.container.lx = s.container.ly = 1.0;
  s.neighbor_skin = 0.1;  // of the diameter: 1 mm
  ParticleStore p;
  p.add_sphere(0, kR, kRho, Vec3(0.5, 0.5, kR), Vec3::Zero(), Vec3::Zero());
  PlaneWall floor{"floor", Vec3::Zero(), Vec3(0, 0, 1), 0.0};
  Simulation sim(s, p, {floor});
  sim.run(10);
  const long builds = sim.diagnostics().neighbor_builds;
  // Ten skins above the sphere's top, coming down at 1 m/s: it touches after 10 ms.
  PlaneWall lid{"lid", Vec3(0, 0, 2 * kR + 0.01), Vec3(0, 0, -1), 0.0};
  lid.velocity = Vec3(0, 0, -1.0);
  sim.add_wall(lid);
  EXPECT_THROW(sim.add_wall(lid), Error) << "wall names are unique";
  sim.run(9990);
  EXPECT_EQ(sim.wall_forces()[1], Vec3::Zero()) << "not there yet";
  sim.run(30);
  EXPECT_GT(sim.wall_forces()[1].z(), 0.0) << "the lid is pressing the sphere";
  EXPECT_GE(sim.diagnostics().neighbor_builds - builds, 15) << "a rebuild every half skin of travel";
  EXPECT_THROW(sim.set_wall_velocity(sim.wall_index("lid"), Vec3(NAN, 0, 0)), Error);
  EXPECT_THROW((void)sim.wall_index("piston"), Error);
}

TEST(MovingWall, AnAddedWallCarriesNoLoadUntilTheNextStep) {
  for (const Summation summation : {Summation::deterministic, Summation::fast}) {
    SCOPED_TRACE(to_string(summation));
    SceneConfig s = test::bare_scene(1e-6);
    s.effects.gravity = true;
    s.effects.energy_tracking = true;
    s.container.lx = s.container.ly = 1.0;
    ParticleStore p;
    p.add_sphere(0, kR, kRho, Vec3(0.5, 0.5, kR), Vec3::Zero(), Vec3::Zero());
    const PlaneWall floor{"floor", Vec3::Zero(), Vec3(0, 0, 1), 0.0};
    EngineOptions o;
    o.summation = summation;
    Simulation running(s, p, {floor}, MPI_COMM_SELF, o);
    running.run(2000);
    const Vec3 on_floor = running.wall_forces()[0];
    ASSERT_LT(on_floor.z(), 0.0) << "the sphere presses on the floor (the force on the wall)";
    // The same engine continued from its state: its loads are the state's until it steps.
    Simulation restored(s, running.capture_state(), MPI_COMM_SELF, o);
    for (Simulation* sim : {&running, &restored}) {
      sim->add_wall({"lid", Vec3(0, 0, 4 * kR), Vec3(0, 0, -1), 0.0});
      const std::vector<Vec3> f = sim->wall_forces();
      ASSERT_EQ(f.size(), sim->walls().size());
      EXPECT_EQ(f[0], on_floor);
      EXPECT_EQ(f[1], Vec3::Zero());
      // Moving it books the work of its (zero) load: nothing read beyond the loads.
      sim->set_wall_velocity(1, Vec3(0, 0, -0.01));
      sim->run(10);
      EXPECT_EQ(sim->wall_forces().size(), sim->walls().size());
      EXPECT_EQ(sim->wall_forces()[1], Vec3::Zero()) << "not there yet";
    }
  }
}
