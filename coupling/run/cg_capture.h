#pragma once
// The states a run keeps for the coarse-grained fields (docs/coarse-graining.md): the
// positions of the reference state (for the displacement field), and at the end the gathered
// grains and contacts of the final evaluation, with a second state a sampling interval later
// when the time derivative is taken by differences. Kept on rank 0; the study evaluates them
// on its mesh.
#include <optional>

#include "dem/engine/simulation.h"
#include "upscale/cg/grain_state.h"

namespace upgrain::coupling {

struct CoarseGrainingCapture {
  bool enabled = false;
  bool displacement = false;    // keep the reference positions
  double reference_time = 0.0;  // s: the first step at or after it is the reference
  long later_steps = 0;         // > 0: a second state this many steps after the final one
};

struct CapturedStates {
  std::optional<upscale::cg::GrainState> final_state, later_state;  // rank 0
  double sampling_interval = 0.0;                                   // s between the two
};

class StateCapture {
 public:
  explicit StateCapture(const CoarseGrainingCapture& options) : options_(options) {}
  // Collective; at each step (and once before the first): takes the reference when due.
  void at_step(dem::Simulation& sim);
  // Collective; a resumed run's reference, as its checkpoint holds it (rank 0's matters).
  void resume(dem::Simulation& sim, const std::optional<upscale::cg::ReferencePositions>& reference);
  // The reference positions taken so far (rank 0), for a checkpoint.
  [[nodiscard]] const std::optional<upscale::cg::ReferencePositions>& reference() const { return reference_; }
  // Collective; at the end of the run: the final state (one recorded step more if the last
  // step recorded no contacts) and, when asked, the later one.
  CapturedStates at_end(dem::Simulation& sim);

 private:
  upscale::cg::GrainState capture(dem::Simulation& sim) const;

  CoarseGrainingCapture options_;
  std::optional<upscale::cg::ReferencePositions> reference_;
  bool reference_taken_ = false;
};

}  // namespace upgrain::coupling
