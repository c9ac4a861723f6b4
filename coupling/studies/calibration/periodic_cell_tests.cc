#include "coupling/studies/calibration/periodic_cell_tests.h"

#include <cmath>
#include <limits>

#include "coupling/run/lid.h"
#include "coupling/studies/element/element_cell.h"
#include "coupling/studies/element/element_options.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// As the lid's: short of its target within this share the servo is still pushing the grains in.
constexpr double kHeldTolerance = 0.05;

// The bed's box of height `height`, every axis periodic, without gravity, under `first`.
dem::SceneConfig cell_scene(dem::SceneConfig scene, double height, const dem::CellMotion& first) {
  scene.container.periodic = {true, true, true};
  scene.container.height = height;
  scene.effects.gravity = false;
  scene.cell = first;
  return scene;
}

// Rank 0's grains of the bed at rest: no velocity, no spin, no crossings yet.
dem::ParticleStore grains_at_rest(const dem::EngineState& bed) {
  dem::ParticleStore p = bed.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v[i] = p.omega[i] = p.force[i] = p.torque[i] = dem::Vec3::Zero();
    p.image[i] = {0, 0, 0};
  }
  return p;
}

long hold_steps(const OedometerOptions& o, double dt) { return steps_of(o.hold_time, dt); }
long seating_steps(const OedometerOptions& o, double dt) { return std::lround(o.seating_time / dt); }

long shearing_steps(const TriaxialOptions& x, double dt) {
  return compression_steps(x.final_strain, x.strain_rate, dt, x.records);
}

dem::CellMotion oedometric(double target, const CellServo& s) {
  dem::CellMotion m;
  m.axis = {cell_rate(0.0), cell_rate(0.0), cell_servo(target, s.gain, s.max_rate)};
  return m;
}

}  // namespace

OedometerRecord deposited_state(const dem::SceneConfig& scene, const dem::EngineState& bed, MPI_Comm comm,
                                const dem::EngineOptions& engine) {
  dem::Simulation sim(scene, bed, comm, engine);
  sim.request_contacts();
  sim.step();
  const double top = highest_grain_top(sim);
  if (!(top > 0.0))
    throw Error("calibration in a periodic cell: the bed's top is not above the floor at z = 0");
  OedometerRecord r = stress_below(sim, top);
  r.lid_stress = kNaN;
  return r;
}

std::vector<OedometerRecord> run_cell_oedometer(const dem::SceneConfig& scene, const dem::EngineState& bed,
                                                const OedometerRecord& deposited, const OedometerOptions& o,
                                                const CellServo& servo, MPI_Comm comm,
                                                const dem::EngineOptions& engine) {
  if (o.lid_stresses.empty()) throw Error("calibration in a periodic cell: no oedometric target");
  ElementCell cell(cell_scene(scene, deposited.height, oedometric(o.lid_stresses.front(), servo)),
                   grains_at_rest(bed), comm, engine, o.after_step);
  const double dt = scene.time_step;
  std::vector<OedometerRecord> records = {deposited};
  cell.run(seating_steps(o, dt), 1);
  const long hold = hold_steps(o, dt);
  for (std::size_t k = 0; k < o.lid_stresses.size(); ++k) {
    const double target = o.lid_stresses[k];
    if (k > 0) cell.control(oedometric(target, servo));
    const dem::Mat3 sigma = cell.run_stress(hold, std::max(1L, hold / 4));
    OedometerRecord r;
    r.time = cell.sim().time();
    r.target = target;
    r.height = cell.lengths()[2];
    r.lid_stress = kNaN;
    r.bagi = sigma;
    r.state.vertical_stress = -sigma(2, 2);
    r.state.horizontal_stress = -0.5 * (sigma(0, 0) + sigma(1, 1));
    r.state.vertical_strain = 1.0 - r.height / deposited.height;
    r.at_rest = std::abs(r.state.vertical_stress - target) <= kHeldTolerance * target;
    records.push_back(r);
  }
  return records;
}

std::vector<TriaxialRecord> run_cell_triaxial(const dem::SceneConfig& scene, const dem::EngineState& bed,
                                              double height, const TriaxialOptions& x, const CellServo& servo,
                                              MPI_Comm comm, const dem::EngineOptions& engine) {
  const dem::CellAxisControl confining = cell_servo(x.confining_stress, servo.gain, servo.max_rate);
  ElementCell cell(cell_scene(scene, height, every_axis(confining)), grains_at_rest(bed), comm, engine,
                   x.after_step);
  const double dt = scene.time_step;
  cell.run(steps_of(x.consolidation_time, dt), 1);
  const std::vector<CellSample> samples =
      drained_triaxial(cell, confining, x.strain_rate, shearing_steps(x, dt), x.records);
  const CellSample& start = samples.front();
  std::vector<TriaxialRecord> out;
  for (const CellSample& c : samples) {
    TriaxialRecord r;
    r.time = c.time;
    r.height = c.lengths[2];
    r.width_x = c.lengths[0];
    r.width_y = c.lengths[1];
    r.lid_stress = kNaN;
    r.side_stress = {kNaN, kNaN, kNaN, kNaN};
    r.bagi = c.stress;
    r.state = triaxial_state(c, start);
    out.push_back(r);
  }
  return out;
}

long cell_oedometer_steps(const OedometerOptions& o, double dt) {
  return seating_steps(o, dt) + static_cast<long>(o.lid_stresses.size()) * hold_steps(o, dt);
}

long cell_triaxial_steps(const TriaxialOptions& x, double dt) {
  return steps_of(x.consolidation_time, dt) + shearing_steps(x, dt);
}

}  // namespace upgrain::coupling
