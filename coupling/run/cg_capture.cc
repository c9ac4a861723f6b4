#include "coupling/run/cg_capture.h"

namespace upgrain::coupling {

void StateCapture::at_step(dem::Simulation& sim) {
  if (!options_.enabled || !options_.displacement || reference_taken_) return;
  if (sim.time() < options_.reference_time - 0.5 * sim.time_step()) return;
  const dem::ParticleStore& all = sim.whole_state();  // collective
  if (sim.is_root()) reference_ = upscale::cg::reference_from(all, sim.time(), &sim.decomposition().cell());
  reference_taken_ = true;
}

void StateCapture::resume(dem::Simulation& sim,
                          const std::optional<upscale::cg::ReferencePositions>& reference) {
  int taken = sim.is_root() && reference ? 1 : 0;
  MPI_Bcast(&taken, 1, MPI_INT, 0, sim.comm());
  reference_taken_ = taken != 0;
  if (sim.is_root()) reference_ = reference;
}

upscale::cg::GrainState StateCapture::capture(dem::Simulation& sim) const {
  const dem::ParticleStore& all = sim.whole_state();
  const std::vector<dem::ContactRecord> contacts = sim.gather_contacts_by_id();
  upscale::cg::GrainState s;
  sim.on_root([&] {
    s = upscale::cg::state_from(all, contacts, sim.gravity(), sim.time(), reference_ ? &*reference_ : nullptr,
                                &sim.decomposition().cell());
  });
  return s;
}

CapturedStates StateCapture::at_end(dem::Simulation& sim) {
  CapturedStates out;
  if (!options_.enabled) return out;
  if (!sim.contacts_recorded()) {
    sim.request_contacts();
    sim.step();
  }
  out.final_state = capture(sim);
  if (options_.later_steps > 0) {
    const double t0 = sim.time();
    if (options_.later_steps > 1) sim.run(options_.later_steps - 1);
    sim.request_contacts();
    sim.step();
    out.later_state = capture(sim);
    out.sampling_interval = sim.time() - t0;
  }
  if (!sim.is_root()) out = CapturedStates{};
  return out;
}

}  // namespace upgrain::coupling
