#pragma once
// The deterministic force loop of the parallel engine (docs/parallel.md). Every pair is
// evaluated once per rank that holds it, in its canonical orientation, into its slot;
// then each owned particle sums its wall contacts by wall index and its pairs by the
// partner's global id. The result is independent of the number of ranks and of local
// indices, bit for bit. Written once as a template on the effect set, like the serial
// loop (contact/force_kernel.h); select_deterministic_forces() picks the instantiation.
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/contact/contact_response.h"
#include "dem/contact/contact_sample.h"
#include "dem/contact/effects.h"
#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/grain_poses.h"
#include "dem/core/material.h"
#include "dem/core/particle_store.h"
#include "dem/parallel/contact_lists.h"

namespace upgrain::dem {

// Per owned particle, written by the kernels with energy tracking: the elastic energy of
// its wall contacts and of the pairs where it is lo (so each pair is counted once, by the
// owner of its lower-id particle), and the viscous part of its total contact force (for
// the second half of the damping work, docs/integrator.md).
struct OwnedEnergyTerms {
  std::vector<double> elastic_normal, elastic_tangential;
  std::vector<Vec3> damping_force;
  std::vector<Vec3> damping_torque;  // its torque about the centroid (ellipsoid scenes)
};

struct DeterministicForceInput {
  ParticleStore* particles = nullptr;  // owned first, then ghosts
  int n_owned = 0;
  ContactLists* lists = nullptr;
  const std::vector<PlaneWall>* walls = nullptr;
  ContactMaterial material;
  double dt = 0.0;
  OwnedEnergyTerms* energy = nullptr;            // required by the energy kernels
  std::vector<ContactSample>* record = nullptr;  // required by the recording kernels
  // Ellipsoid kernels: every local grain posed once per evaluation (owned and ghosts), and
  // the contact solver's counters of this rank, cumulative.
  GrainPoses* posed = nullptr;
  ContactSolverStats* solver_stats = nullptr;
};

struct DeterministicForceResult {
  long pair_contacts = 0;  // touching pairs whose lo is owned (so each pair once over the ranks)
  long wall_contacts = 0;
  double max_overlap_ratio = 0.0;
  // With energy tracking: this evaluation's dissipation on this rank, over the wall
  // contacts of owned particles and the pairs whose lo is owned (elastic fields unused).
  ContactEnergy dissipated;
};

using DeterministicForceKernel = DeterministicForceResult (*)(const DeterministicForceInput&);

// The same loop without and with contact recording (stress output). The recording kernel
// writes every contact of the owned particles, once per rank: wall contacts (a = the
// particle, b = -(w + 1)), then pairs in slot order (a = lo, b = hi, force on lo, point
// x_lo + (r_lo - delta / 2) n); a pair straddling two ranks is recorded on both.
struct DeterministicForceKernels {
  DeterministicForceKernel plain;
  DeterministicForceKernel recording;
};

// `shapes`: the scene holds ellipsoids (the lists then keep contact memory); the contact
// geometry and law are those of the serial loop (contact/shaped_contact.h).
DeterministicForceKernels select_deterministic_forces(const EffectSet& effects, bool shapes = false);

}  // namespace upgrain::dem
