#pragma once
// A pour (docs/insertion.md): the scene's Insertion section run against the engine. Before
// each step it asks whether a batch is due; if so, it gathers the bounding spheres of the
// grains in the inlet from every rank, places the batch's grains by the plain, deterministic
// place_in_inlet() (dem/scene/insertion.h), the same on every rank, and hands them to the
// engine (Simulation::insert()), which gives each to the rank that owns its position. Ids,
// positions and orientations depend on the scene and the batch index only: the pour is the
// same on any rank count, and its state (two counts) is what a checkpoint keeps of it.
#include "dem/engine/simulation.h"
#include "dem/scene/insertion.h"

namespace upgrain::dem {

// Where a pour stands: grains inserted and batches done (a checkpoint's part, docs/restart.md).
struct PourState {
  long inserted = 0;
  long batches = 0;
};

class Pour {
 public:
  explicit Pour(const SceneConfig& scene, PourState state = {});

  [[nodiscard]] bool enabled() const { return scene_.insertion.enabled(); }
  // Every grain of the pour is in (or the scene pours nothing).
  [[nodiscard]] bool done() const { return state_.inserted >= scene_.insertion.count; }
  [[nodiscard]] const PourState& state() const { return state_; }
  // The step (of the engine's count) before which batch b goes in.
  [[nodiscard]] long step_of_batch(long b) const;
  // Inserts the batch due before the engine's next step, if one is. Collective.
  void before_step(Simulation& sim);

 private:
  SceneConfig scene_;
  PourPlan plan_;
  PourState state_;
};

}  // namespace upgrain::dem
