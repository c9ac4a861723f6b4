#include "coupling/calibration/oedometer_run.h"

#include <algorithm>
#include <cmath>

#include "coupling/run/lid.h"
#include "coupling/run/stop_request.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

// The bed's mean stress over the box from the floor to the lid (one Bagi cell); needs a step
// that recorded its contacts.
OedometerRecord measure(const dem::Simulation& sim, double target, double first_height) {
  const dem::SceneConfig& scene = sim.scene();
  const long lid = Lid::index(sim);
  OedometerRecord r;
  r.time = sim.time();
  r.target = target;
  r.height = sim.walls()[static_cast<std::size_t>(lid)].point.z();
  r.lid_stress = Lid::stress(sim);
  dem::RegularGrid grid;
  grid.lo = dem::Vec3::Zero();
  grid.hi = dem::Vec3(scene.container.lx, scene.container.ly, r.height);
  r.bagi = sim.grid_stress(grid)[dem::StressFormula::bagi][0];
  r.state.vertical_stress = -r.bagi(2, 2);
  r.state.horizontal_stress = -0.5 * (r.bagi(0, 0) + r.bagi(1, 1));
  r.state.vertical_strain = (first_height - r.height) / first_height;
  return r;
}

// Steps between checks for a stop request (SIGINT, SIGTERM, SIGHUP; one collective each).
constexpr long kStopCheckEvery = 1000;

long hold_steps(const OedometerOptions& o, double dt) { return std::max(1L, std::lround(o.hold_time / dt)); }
long seating_steps(const OedometerOptions& o, double dt) { return std::lround(o.seating_time / dt); }

void step(dem::Simulation& sim, const OedometerOptions& o) {
  sim.step();
  if (o.after_step) o.after_step();
}

}  // namespace

std::vector<OedometerRecord> run_oedometer(dem::Simulation& sim, const OedometerOptions& o) {
  LidControl control;
  control.mode = LidControl::Mode::servo;
  control.place_time = sim.time();
  control.target_stresses = o.lid_stresses;
  control.step_duration = o.hold_time;
  control.gain_factor = o.gain_factor;
  control.max_speed = o.max_speed;
  control.update_every = o.update_every;
  validate_lid(control, [&] {
    dem::SceneConfig s = sim.scene();
    s.end_time = sim.time() + o.seating_time + o.hold_time * static_cast<double>(o.lid_stresses.size()) +
                 sim.time_step();
    return s;
  }());
  Lid lid(control);
  const long hold = hold_steps(o, sim.time_step());
  std::vector<OedometerRecord> records;
  // The unloaded bed: the lid placed (on its highest grain, touching nothing), one recorded step.
  lid.before_step(sim);
  const auto lid_index = static_cast<std::size_t>(Lid::index(sim));
  sim.set_wall_velocity(lid_index, dem::Vec3::Zero());  // still for this step
  const double first_height = sim.walls()[lid_index].point.z();
  if (!(first_height > 0.0)) throw Error("oedometric test: the bed's top is not above the floor at z = 0");
  sim.request_contacts();
  step(sim, o);
  records.push_back(measure(sim, 0.0, first_height));
  // The seating at the first target, then the holds: target k from k hold times after it.
  const long seating = seating_steps(o, sim.time_step());
  control.place_time = sim.time() + static_cast<double>(seating) * sim.time_step();
  for (long s = 0; s < seating; ++s) {
    lid.before_step(sim);
    if (sim.step_count() % kStopCheckEvery == 0) stop_if_requested(sim.comm(), sim.step_count());
    step(sim, o);
  }
  for (double target : o.lid_stresses) {
    for (long s = 0; s < hold; ++s) {
      lid.before_step(sim);
      if (s + 1 == hold) sim.request_contacts();
      if (sim.step_count() % kStopCheckEvery == 0) stop_if_requested(sim.comm(), sim.step_count());
      step(sim, o);
    }
    records.push_back(measure(sim, target, first_height));
  }
  return records;
}

long oedometer_steps(const OedometerOptions& o, double dt) {
  return 1 + seating_steps(o, dt) + hold_steps(o, dt) * static_cast<long>(o.lid_stresses.size());
}

}  // namespace upgrain::coupling
