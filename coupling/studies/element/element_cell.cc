#include "coupling/studies/element/element_cell.h"

#include <algorithm>
#include <utility>

#include "coupling/run/stop_request.h"

namespace upgrain::coupling {

namespace {

constexpr long kStopCheckEvery = 1000;

}  // namespace

ElementCell::ElementCell(dem::SceneConfig scene, dem::ParticleStore grains, MPI_Comm comm,
                         const dem::EngineOptions& engine, std::function<void()> after_step)
    : scene_(std::move(scene)), comm_(comm), after_step_(std::move(after_step)) {
  sim_ = std::make_unique<dem::Simulation>(scene_, std::move(grains), std::vector<dem::PlaneWall>{}, comm_,
                                           engine);
}

void continue_under(dem::SceneConfig& scene, dem::EngineState& s, const dem::CellMotion& m) {
  for (int d = 0; d < 3; ++d)
    if (m.axis[d].mode == dem::CellAxisMode::rate) s.cell.velocity_gradient(d, d) = m.axis[d].rate;
  if (m.shear.any()) {
    s.cell.velocity_gradient(m.shear.shear(), m.shear.gradient()) = m.shear.rate;
    if (!s.cell.shear.any()) {
      s.cell.shear = dem::ShearImages{m.shear.shear(), m.shear.gradient(), 0.0, 0};
      s.cell.offset_at_build = 0.0;
    }
  }
  const double growth = scene.cell.max_growth;
  scene.cell = m;
  scene.cell.max_growth = growth;
}

void ElementCell::resume(dem::EngineState s, const dem::CellMotion& m) {
  continue_under(scene_, s, m);
  const dem::EngineOptions engine = sim_->options();
  sim_.reset();
  sim_ = std::make_unique<dem::Simulation>(scene_, s, comm_, engine);
}

dem::Mat3 ElementCell::run_stress(long steps, long window) {
  dem::Mat3 sum = dem::Mat3::Zero();
  for (long k = 0; k < steps; ++k) {
    sim_->step();
    if (k >= steps - window) sum += sim_->cell_stress();
    if (after_step_) after_step_();
    // A stop request (SIGINT, SIGTERM, SIGHUP) ends the test within this many steps; one
    // collective each.
    if (sim_->step_count() % kStopCheckEvery == 0) stop_if_requested(comm_, sim_->step_count());
  }
  return sum / static_cast<double>(std::max(window, 1L));
}

namespace {

CellSample sample_of(ElementCell& cell, double time, const dem::Mat3& stress) {
  return {time, cell.lengths(), cell.volume(), stress, cell.sim().diagnostics().particle_contacts};
}

}  // namespace

dem::TriaxialState triaxial_state(const CellSample& c, const CellSample& start) {
  dem::TriaxialState s;
  s.axial_strain = 1.0 - c.lengths[2] / start.lengths[2];
  s.volumetric_strain = 1.0 - c.volume / start.volume;
  s.axial_stress = -c.stress(2, 2);
  s.lateral_stress = 0.5 * (-c.stress(0, 0) + -c.stress(1, 1));
  return s;
}

std::vector<CellSample> drained_triaxial(ElementCell& cell, const dem::CellAxisControl& lateral,
                                         double axial_rate, long steps, long records) {
  dem::CellMotion m;
  m.axis = {lateral, lateral, cell_rate(-axial_rate)};
  cell.control(m);
  std::vector<CellSample> out;
  out.push_back(sample_of(cell, 0.0, cell.sim().cell_stress()));
  const long per_record = steps / records;
  const double dt = cell.sim().time_step();
  for (long k = 1; k <= records; ++k) {
    const dem::Mat3 stress = cell.run_stress(per_record, per_record);
    out.push_back(sample_of(cell, static_cast<double>(k * per_record) * dt, stress));
  }
  return out;
}

}  // namespace upgrain::coupling
