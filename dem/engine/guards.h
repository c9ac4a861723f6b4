#pragma once
// The engine's guards: a run whose state left the physics stops with a diagnosis instead of
// writing nonsense (docs/architecture.md, "Guards"). Each check is a plain function over the
// rank's data that returns the diagnosis, empty when the state is sound; the engine makes it
// collective (every rank throws the first rank's message) and calls them:
//  - non-finite state: at every neighbour-list rebuild and every output;
//  - runaway overlap: after every force evaluation, in the step's one reduction;
//  - lost particle: after every migration (the global count), and at every output (the
//    gathered state: count, repeated ids, total mass).
#include <string>

#include "dem/core/particle_store.h"
#include "dem/scene/scene_config.h"
#include "dem/scene/weight_overlap.h"

namespace upgrain::dem {

// The first of owned particles [0, n_owned) whose position, velocity, angular velocity or
// orientation (stores with shapes) is not finite, named with the step and time.
std::string non_finite_state(const ParticleStore& p, int n_owned, long step, double time);

// The contact of the largest overlap: global ids of the particle and its partner, or, for a
// wall, partner = -(w + 1) and the wall's name. particle = -1: not known (nothing is named).
struct OverlapSite {
  GlobalId particle = -1;
  GlobalId partner = -1;
  std::string wall;
};

// An overlap above `limit` of the smallest semi-axis at the evaluation of `step`, naming its
// contact, with its cause: a grain passing through a wall (an overlap of a whole semi-axis at
// a wall), grains too soft for their weight or for the stress of the cell they fill (`load`,
// when known; dem/scene/weight_overlap.h), or a time step too large for the impacts.
std::string runaway_overlap(double ratio, double limit, long step, double time, const SceneConfig& scene,
                            const OverlapSite& site = {}, const AssemblyLoad& load = {});

// The global particle count after a migration differs from the scene's.
std::string lost_particles(long count, long expected, long step);

// The gathered state (sorted by id) has another count, a repeated id or another mass than the
// reference (summed in id order, so the same bits at every output).
std::string inconsistent_state(const ParticleStore& sorted, long expected_count, double mass,
                               double expected_mass, long step);
// The same from its figures: `count` particles, `unique` when every id appears once (for the
// slices of Simulation::whole_state_slice(): each slice holds exactly its rows' ids).
std::string inconsistent_state(long count, bool unique, long expected_count, double mass,
                               double expected_mass, long step);

}  // namespace upgrain::dem
