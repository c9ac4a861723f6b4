#pragma once
// Initial placement of the grains: a jittered lattice or a random non-overlapping fill of
// the container's cross-section above an optional bottom gap.
#include <vector>

#include "dem/core/particle_store.h"
#include "dem/scene/scene_config.h"

namespace upgrain::dem {

struct FillPlan {
  std::vector<double> radii;  // one per particle, in id order
  double top = 0.0;           // height of the highest particle surface (m)
};

// Radii and the fill height, without placing anything (used by the time-step estimate); of an
// initial packing, its grains' radii and top.
FillPlan plan_fill(const SceneConfig& scene);

double fill_top_height(const SceneConfig& scene);

// Places the particles; ids are 0..count-1. Throws upgrain::Error when they do not fit. A
// scene with an initial packing (ParticleSpec::packing) returns its grains.
ParticleStore fill_container(const SceneConfig& scene);

}  // namespace upgrain::dem
