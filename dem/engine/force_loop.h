#pragma once
// The force loop: every pair slot and wall entry of the lists (dem/core/pair_list.h) is
// evaluated once per evaluation, its history read and written in the contact-history store,
// and its force and torques added to both bodies in the order of the lists. The lists'
// order is the summation (dem/neighbor/verlet_list.h, dem/engine/summation.h), so the same
// loop serves both: only where the sums start and where the energies are booked differ.
//
// Written once, as a template on the contact law (dem/contact/contact_laws.h), the effect
// set (dem/contact/effects.h), on whether the scene has grains other than spheres (then the
// geometry of each pair comes from the table of dem/contact/geometry/pair_geometries.h), on
// contact recording and on the summation. select_force_loops()
// turns the scene's run-time choices into one instantiation, chosen once per run, so what a
// scene switches off is not computed (docs/architecture.md).
#include <string_view>
#include <vector>

#include <array>

#include "dem/contact/contact_laws.h"
#include "dem/contact/contact_response.h"
#include "dem/contact/contact_sample.h"
#include "dem/contact/effects.h"
#include "dem/contact/geometry/pair_geometries.h"
#include "dem/contact/grain_poses.h"
#include "dem/contact/rolling_resistance.h"
#include "dem/core/cell_motion.h"
#include "dem/core/contact_history.h"
#include "dem/core/material.h"
#include "dem/core/pair_list.h"
#include "dem/core/particle_store.h"
#include "dem/core/plane_wall.h"
#include "dem/engine/summation.h"

namespace upgrain::dem {

// What an evaluation leaves besides the forces and torques in the store.
struct ForceOutput {
  // Energy tracking with damping: the viscous part of each local particle's contact force
  // and, for ellipsoids, its torque; with rolling resistance, the viscous rolling torque. For
  // the second half of their work (docs/integrator.md).
  std::vector<Vec3> damping_force, damping_torque, rolling_damping_torque;
  // Deterministic summation with energy tracking: each local particle's elastic energies, of
  // its wall contacts and of the pairs it is first (lower id) in, so that every pair counts
  // once over the ranks and the sum can run in global-id order.
  std::vector<ElasticEnergy> particle_elastic;
  // Fast: the force of the particles on each wall. Deterministic: the force on the particle of
  // each wall entry (zero when apart), summed per wall in global-id order for the output.
  std::vector<Vec3> wall_force;
  // Energy tracking with damping: the dashpot's part of wall_force, in the same layout (the
  // wall's part of the dashpot's work, docs/integrator.md "Moving walls").
  std::vector<Vec3> wall_damping;
  // Recording loops: every contact evaluated (a = the slot's first particle or the particle
  // at a wall, b = the partner or -(w + 1); the force on a, the contact point).
  std::vector<ContactSample> contacts;
  // Fast: the energies of every contact (elastic and dissipated), this rank's sums.
  ContactEnergy energy;
  long pair_contacts = 0;  // touching pairs (deterministic: whose first particle is owned)
  long wall_contacts = 0;
  double max_overlap_ratio = 0.0;  // max of overlap / smallest semi-axis
  // The contact of that overlap, for the runaway-overlap guard's diagnosis (guards.h): the
  // global ids of its particle and partner, or -(w + 1) for wall w; -1 without contacts.
  GlobalId max_overlap_particle = -1;
  GlobalId max_overlap_partner = -1;
  // Scenes with non-spherical grains, per chunk of rows (buffers reused): the class of each
  // slot, and per batched geometry the pairs past their bounding spheres
  // (dem/contact/geometry/pair_geometries.h).
  std::vector<unsigned char> slot_class;
  std::array<std::vector<ShapedPair>, kBatchedPairGeometries> shaped_pairs;
};

// Plain views of what one evaluation reads and writes.
struct ForceInput {
  ParticleStore* particles = nullptr;  // owned first, then ghosts
  int n_owned = 0;
  const PairList* pairs = nullptr;
  const WallList* wall_entries = nullptr;
  const std::vector<PlaneWall>* walls = nullptr;
  ContactHistory* history = nullptr;
  // Deterministic summation with energy tracking: each owned particle's dissipation since the
  // last rebuild, to which the evaluation adds (its wall contacts and the pairs it is first in).
  DissipatedEnergy* dissipation = nullptr;
  ContactMaterial material;           // friction between grains, damping ratio
  const LawConstants* law = nullptr;  // the constants of the law the loop was compiled for
  RollingParameters rolling;          // scenes with rolling resistance
  double dt = 0.0;
  // A deforming periodic cell: its velocity gradient L, diagonal but for at most one shear
  // component (null otherwise). The store then holds peculiar velocities u = v - L x (SLLOD), and
  // a contact's relative velocity takes the mean flow's L (x_j - x_i) besides; the branch
  // x_j - x_i is exact on the cell's grid, so the two sides of a pair across a face see the same
  // bits (docs/periodic.md, "A cell that deforms").
  const MeanFlow* mean_flow = nullptr;
  // Ellipsoid scenes: every local grain posed once per evaluation, and this rank's contact
  // solver counters, cumulative.
  GrainPoses* posed = nullptr;
  ContactSolverSettings solver_settings;  // the scene's (SceneConfig::contact_solver)
  ContactSolverStats* solver_stats = nullptr;
  ForceOutput* out = nullptr;
};

using ForceLoop = void (*)(const ForceInput&);

// The same loop without and with contact recording (stress output), so the steps between
// outputs pay nothing for it.
struct ForceLoops {
  ForceLoop plain;
  ForceLoop recording;
  // The effects the two loops were compiled with (what a frictionless scene leaves out, for
  // tests and the run's report): rotation as the loop does it, so off for spheres without a
  // torque; gravity is not the loop's.
  EffectSet compiled;
  const char* law = "";  // the contact law's name (dem/contact/contact_laws.h)
};

// `shapes`: the store holds ellipsoids; the sphere-only loops carry no shape branch at all.
// `law`: a name of the contact-law table (Contact/law).
ForceLoops select_force_loops(const EffectSet& effects, bool shapes, Summation summation,
                              std::string_view law);

}  // namespace upgrain::dem
