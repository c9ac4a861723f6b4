#pragma once
// The whole state of the engine between two steps, independent of the decomposition: what a
// checkpoint keeps of the DEM (docs/restart.md). Simulation::capture_state() gathers it on
// rank 0; the restoring constructor of Simulation continues from it on any number of ranks,
// and with the deterministic summation the run goes on with the same bits as if it had not
// stopped.
//
// Why each part is there:
//  - the particles with the forces and torques of the last evaluation (the next step's first
//    half kick uses them), and the last evaluation's damping forces and torques (the second
//    half of their work) and each grain's share of its energies, and its dissipation since the
//    last rebuild (added to the exact sums at the next one);
//  - the positions at the last neighbour-list build (the walls' too): the restored lists are built from them,
//    so they hold the same pairs as the interrupted run's, and the next rebuild comes at the
//    same step (the skin test is against them);
//  - every contact history, separation budgets of ellipsoid pairs included;
//  - the walls (removed ones far behind their plane), the step, the rebuild count, the guard's
//    last overlap, the initial energy, gravity, and the exact sums of the dissipation;
//  - the blocks' planes and the load balance's progress, taken again on the same blocks;
//  - a deforming cell's state (CellRecord).
#include <array>
#include <cstdint>
#include <vector>

#include "dem/contact/contact_parameters.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/core/contact_history.h"
#include "dem/core/particle_store.h"
#include "dem/core/plane_wall.h"
#include "dem/engine/energy.h"
#include "dem/parallel/domain.h"
#include "dem/parallel/exact_sum.h"

namespace upgrain::dem {

// A deforming periodic cell between two steps (docs/periodic.md, "A cell that deforms"): its
// present box is the decomposition's (DomainState::box).
struct CellRecord {
  bool deforming = false;
  Box start;     // the box its position grid was sized from (make_periodic_cell()): the quantum
  Box at_build;  // the cell at the last list build: the rebuild check, the lists' image shifts
  Mat3 velocity_gradient = Mat3::Zero();  // L of the next step (the servo's state)
  Mat3 stress = Mat3::Zero();             // the last evaluation's cell stress
  Mat3 stress_volume = Mat3::Zero();      // times its volume: the first end of the work's trapezoid
  bool stress_known = false;
  double work = 0.0;  // the cell's work so far
  // A sheared cell: its sliding images now (periodic_cell.h), and their offset at the last list
  // build (the turns change only at a build). Kept apart from the row below (shear_values()), so
  // that a cell that is not sheared keeps its checkpoint's layout.
  ShearImages shear;
  double offset_at_build = 0.0;

  // As one row of numbers (checkpoint files and the state's bytes), and back.
  static constexpr int kValues = 1 + 12 + 27 + 2;
  [[nodiscard]] std::array<double, kValues> values() const {
    std::array<double, kValues> v{};
    std::size_t k = 0;
    v[k++] = deforming ? 1.0 : 0.0;
    for (const Vec3* x : {&start.lo, &start.hi, &at_build.lo, &at_build.hi})
      for (int d = 0; d < 3; ++d) v[k++] = (*x)[d];
    for (const Mat3* m : {&velocity_gradient, &stress, &stress_volume})
      for (int i = 0; i < 9; ++i) v[k++] = m->data()[i];
    v[k++] = stress_known ? 1.0 : 0.0;
    v[k++] = work;
    return v;
  }
  static constexpr int kShearValues = 5;
  [[nodiscard]] std::array<double, kShearValues> shear_values() const {
    return {static_cast<double>(shear.shear), static_cast<double>(shear.gradient), shear.offset,
            static_cast<double>(shear.turns), offset_at_build};
  }
  void set_shear_values(const std::array<double, kShearValues>& v) {
    shear = {static_cast<int>(v[0]), static_cast<int>(v[1]), v[2], static_cast<std::int64_t>(v[3])};
    offset_at_build = v[4];
  }
  static CellRecord from_values(const std::array<double, kValues>& v) {
    CellRecord c;
    std::size_t k = 0;
    c.deforming = v[k++] != 0.0;
    for (Vec3* x : {&c.start.lo, &c.start.hi, &c.at_build.lo, &c.at_build.hi})
      for (int d = 0; d < 3; ++d) (*x)[d] = v[k++];
    for (Mat3* m : {&c.velocity_gradient, &c.stress, &c.stress_volume})
      for (int i = 0; i < 9; ++i) m->data()[i] = v[k++];
    c.stress_known = v[k++] != 0.0;
    c.work = v[k++];
    return c;
  }
};

struct EngineState {
  static constexpr int kVersion = 2;  // 2: moving walls, the work of walls

  // Per particle, sorted by global id.
  ParticleStore particles;
  std::vector<Vec3> positions_at_build;
  std::vector<Vec3> damping_force, damping_torque, rolling_damping_torque;  // empty when not kept
  // Deterministic summation with energy tracking: each grain's elastic energies of the last
  // evaluation, and its dissipation since the last rebuild (not yet in the exact sums).
  std::vector<ElasticEnergy> particle_elastic;
  std::vector<DissipatedEnergy> dissipation_share;

  std::vector<ContactHistoryRecord> history;  // sorted by key, separation budgets kept
  std::vector<PlaneWall> walls;               // with their velocities
  std::vector<Vec3> wall_points_at_build;     // the walls' points at the last list build

  // What the last evaluation counted and exerted (StepDiagnostics, Simulation::wall_forces()),
  // over every rank, for a restart that asks before its first step.
  long pair_contacts = 0, wall_contacts = 0;
  std::vector<Vec3> wall_forces;
  std::vector<Vec3> wall_damping_forces;  // the dashpot's part of wall_forces

  long step = 0;
  long rebuilds = 0;
  bool rebuild_pending = false;
  double last_overlap_ratio = 0.0;
  long last_overlap_step = 0;
  Vec3 gravity = Vec3::Zero();
  EnergyBalance initial_energy;
  double removed_by_relaxation = 0.0;
  static constexpr int kDissipationChannels = 6;
  std::array<std::array<std::int64_t, ExactSum::kDigits + 1>, kDissipationChannels> dissipated{};
  ContactSolverStats solver_stats;  // over every rank
  double reference_mass = -1.0;     // of the first checked gather (the lost-particle guard)
  DomainState domain;
  CellRecord cell;
};

// The whole state as bytes and back, every bit kept: the restoring constructor's broadcast, and a
// state that moves between ranks or into a file as one block (a DEM cell of FEM x DEM). The
// bytes are not a file format: both ends are the same build.
[[nodiscard]] std::vector<char> to_bytes(const EngineState& s);
[[nodiscard]] EngineState from_bytes(const std::vector<char>& bytes);

}  // namespace upgrain::dem
