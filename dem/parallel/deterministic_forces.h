#pragma once
// The deterministic force loop of the parallel engine (docs/parallel.md). Every pair is
// evaluated once per rank that holds it, in its canonical orientation, into its slot;
// then each owned particle sums its wall contacts by wall index and its pairs by the
// partner's global id. The result is independent of the number of ranks and of local
// indices, bit for bit. Written once as a template on the effect set, like the serial
// loop (contact/force_kernel.h); select_deterministic_forces() picks the instantiation.
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/contact/effects.h"
#include "dem/core/material.h"
#include "dem/core/particle_store.h"
#include "dem/parallel/contact_lists.h"

namespace upgrain::dem {

struct DeterministicForceInput {
  ParticleStore* particles = nullptr;  // owned first, then ghosts
  int n_owned = 0;
  ContactLists* lists = nullptr;
  const std::vector<PlaneWall>* walls = nullptr;
  ContactMaterial material;
  double dt = 0.0;
};

struct DeterministicForceResult {
  long pair_contacts = 0;  // pairs touching, counted on this rank (straddling pairs on both)
  long wall_contacts = 0;
  double max_overlap_ratio = 0.0;
};

using DeterministicForceKernel = DeterministicForceResult (*)(const DeterministicForceInput&);

DeterministicForceKernel select_deterministic_forces(const EffectSet& effects);

}  // namespace upgrain::dem
