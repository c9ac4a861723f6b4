#pragma once
// The force loop over particle pairs and particle-wall contacts. It is written once as a
// template on the effect set; select_force_kernel() turns the scene's run-time choices
// into one instantiation, chosen once per run.
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/contact/contact_response.h"
#include "dem/contact/contact_sample.h"
#include "dem/contact/effects.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/grain_poses.h"
#include "dem/contact/rolling_resistance.h"
#include "dem/contact/shaped_contact.h"
#include "dem/core/material.h"
#include "dem/core/particle_store.h"
#include "dem/neighbor/verlet_list.h"
#include "dem/neighbor/wall_list.h"

namespace upgrain::dem {

struct ForceContext {
  ParticleStore* particles = nullptr;
  VerletList* neighbors = nullptr;
  const std::vector<PlaneWall>* walls = nullptr;
  WallNeighborList* wall_neighbors = nullptr;
  ContactMaterial material;
  RollingParameters rolling;  // used by the kernels of scenes with rolling resistance
  double dt = 0.0;

  // Results of one evaluation.
  ContactEnergy energy;  // elastic: current; dissipated: this step's increment
  long particle_contacts = 0;
  long wall_contacts = 0;
  double max_overlap_ratio = 0.0;  // max of delta / min(r_i, r_j)
  std::vector<Vec3> wall_force;    // total force exerted by particles on each wall
  // Viscous part of the contact force on each particle (energy tracking with damping),
  // for the second half of the damping work (docs/integrator.md).
  std::vector<Vec3> damping_force;
  // Its torque about the centroids (ellipsoid scenes: the normal misses the centroid).
  std::vector<Vec3> damping_torque;
  // Viscous part of the rolling resistance torque on each particle (rolling resistance with
  // energy tracking), for the second half of its work.
  std::vector<Vec3> rolling_damping_torque;
  // Ellipsoid contact solver counters, cumulative over the run (reported in the log).
  ContactSolverStats solver_stats;
  // Every grain posed once per evaluation (rotation and shape matrices, motion bounds;
  // ellipsoid scenes).
  GrainPoses posed;
  // Ellipsoid scenes, per chunk of rows (buffers reused): the class of each pair slot and the
  // shaped pairs past their bounding spheres.
  std::vector<unsigned char> slot_class;
  std::vector<ShapedPair> shaped_pairs;
  // Every contact of the evaluation, in the loop's order (recording kernels only).
  std::vector<ContactSample> contacts;
};

using ForceKernel = void (*)(ForceContext&);

// The same force loop twice: without and with contact recording (for stress output), so
// the steps between outputs pay nothing for it.
struct ForceKernels {
  ForceKernel plain;
  ForceKernel recording;
};

// `shapes`: the store holds ellipsoids (ParticleStore::has_shapes()); the sphere-only
// loops carry no shape branch at all.
ForceKernels select_force_kernels(const EffectSet& effects, bool shapes = false);

}  // namespace upgrain::dem
