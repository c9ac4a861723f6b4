#include "dem/engine/pour.h"

#include <cmath>
#include <random>
#include <span>

#include "dem/scene/grain_shape.h"

namespace upgrain::dem {

Pour::Pour(const SceneConfig& scene, PourState state)
    : scene_(scene), plan_(plan_pour(scene)), state_(state) {}

long Pour::step_of_batch(long b) const {
  const InsertionSpec& in = scene_.insertion;
  return std::llround((in.start_time + static_cast<double>(b) * in.interval) / scene_.time_step);
}

void Pour::before_step(Simulation& sim) {
  if (!enabled() || done() || sim.step_count() < step_of_batch(state_.batches)) return;
  const long b = state_.batches++;
  const long want = grains_due(scene_.insertion, plan_, b) - state_.inserted;
  if (want <= 0) return;
  const InsertionSpec& in = scene_.insertion;
  const Box inlet{in.inlet_lo, in.inlet_hi};
  // Every grain that could overlap a candidate reaches into the inlet, where the candidates lie
  // whole: these obstacles are all there are, the same on every rank.
  const std::vector<BoundingSphere> obstacles = sim.bounding_spheres_in(inlet);
  const std::uint64_t seed = batch_seed(scene_, b);
  const std::span<const double> radii(plan_.radius.data() + state_.inserted, static_cast<std::size_t>(want));
  const std::vector<Vec3> x = place_in_inlet(inlet, radii, obstacles, seed);
  // Orientations from a stream of their own: the positions do not depend on the shapes.
  std::mt19937_64 turn(seed ^ 0x9e3779b97f4a7c15ULL);
  const std::vector<GrainShape>& shapes = scene_.particles.shapes;
  const double density = scene_.particles.material.density;
  ParticleStore batch;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const std::size_t g = static_cast<std::size_t>(state_.inserted) + k;
    const GlobalId id = static_cast<GlobalId>(sim.particle_count()) + static_cast<GlobalId>(k);
    const GrainShape shape = shapes.empty() ? GrainShape{} : shapes[static_cast<std::size_t>(plan_.shape[g])];
    const Eigen::Quaterniond q = random_orientation(turn);  // drawn for spheres too
    add_grain(batch, shape, id, plan_.radius[g], density, q, {x[k], in.velocity, Vec3::Zero()});
  }
  sim.insert(batch);
  state_.inserted += static_cast<long>(x.size());
}

}  // namespace upgrain::dem
