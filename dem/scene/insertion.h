#pragma once
// Insertion during the run (docs/insertion.md): which grains a pour brings and when, and where
// a batch of them goes in the inlet box. Plain functions over plain data, the same on every
// rank: the engine's hand-over (dem/engine/pour.h) calls them with the same arguments on each.
#include <cstdint>
#include <span>
#include <vector>

#include "dem/core/box.h"
#include "dem/scene/scene_config.h"

namespace upgrain::dem {

// Throws upgrain::Error naming the Insertion entry that is wrong: an inlet outside the
// container or too small for the largest grain, a rate, count or interval that is not
// positive, a start after the end time, or a batch the inlet cannot take.
void validate_insertion(const SceneConfig& scene);

// Random sequential addition jams near a solid fraction of 0.38 (Widom 1966; Feder 1980): a
// batch that needs more than this share of the inlet would mostly wait for the next one.
inline constexpr double kBatchFillLimit = 0.3;

// What a pour asks of its inlet: the share of the inlet's volume one batch fills, and the share
// the batches fill that lie in it together while a grain placed at its top falls out of it
// (from the insertion velocity under gravity). Above kBatchFillLimit grains wait, and the pour
// falls behind its rate.
struct InletLoad {
  long grains_per_batch = 0;
  double batch = 0.0;
  double held = 0.0;
};
InletLoad inlet_load(const SceneConfig& scene);

// The grains of the whole pour, drawn once from the scene's seed: grain k's major semi-axis
// (Particles/radius or the gradation), its shape (a row of Particles/shapes) and the mass of
// grains 0..k (for a mass rate).
struct PourPlan {
  std::vector<double> radius;
  std::vector<int> shape;  // empty: every grain a sphere
  std::vector<double> cumulative_mass;
  double largest_radius = 0.0;
};
PourPlan plan_pour(const SceneConfig& scene);

// Grains due in all at the end of batch b (batch 0 at the start time, then every interval):
// rate x elapsed time, or the grains whose mass fits under mass rate x elapsed time, at most
// the count.
long grains_due(const InsertionSpec& spec, const PourPlan& plan, long batch);

// The time of the batch that brings the pour's last grain when every batch goes in whole (a
// full inlet delays it).
double last_batch_time(const SceneConfig& scene, const PourPlan& plan);

// The seed of batch b's positions and orientations: the same for a batch whichever rank or run
// draws it.
std::uint64_t batch_seed(const SceneConfig& scene, long batch);

// A grain already in the container, by its bounding sphere (an ellipsoid's major semi-axis).
struct BoundingSphere {
  Vec3 x;
  double radius;
};

// Places grains of the given bounding radii, in order, inside `inlet` (each wholly inside it) by
// random sequential addition: a candidate centre is drawn uniformly from the box shrunk by the
// grain's radius and kept when its bounding sphere overlaps neither an obstacle's nor a grain's
// placed before it; up to `attempts` candidates per grain. Stops at the first grain that finds
// no place and returns the positions of those placed (a prefix of `radii`), so that the grains
// left wait for the next batch in their order. Deterministic: the same arguments give the same
// bits.
std::vector<Vec3> place_in_inlet(const Box& inlet, std::span<const double> radii,
                                 std::span<const BoundingSphere> obstacles, std::uint64_t seed,
                                 int attempts = 500);

}  // namespace upgrain::dem
