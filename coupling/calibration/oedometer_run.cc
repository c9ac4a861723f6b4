#include "coupling/calibration/oedometer_run.h"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "coupling/run/lid.h"
#include "coupling/run/stop_request.h"
#include "dem/core/error.h"
#include "dem/parallel/exact_sum.h"

namespace upgrain::coupling {

namespace {

// A lid state is at rest when the lid holds its target within this share: short of it, the lid is
// still pushing the bed in.
constexpr double kHeldTolerance = 0.05;

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
  r.at_rest = target > 0.0 && std::abs(r.lid_stress - target) <= kHeldTolerance * target;
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

std::vector<OedometerRecord> run_lid_oedometer(dem::Simulation& sim, const OedometerOptions& o) {
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

// --- By gravity.

// The bed's mass and the sum of m z over its grains, exact (the same bits on any rank count).
struct MassMoment {
  double mass = 0.0, moment = 0.0;
  [[nodiscard]] double centroid() const { return moment / mass; }
};
MassMoment mass_moment(const dem::Simulation& sim) {
  const dem::ParticleStore& p = sim.particles();
  std::array<dem::ExactSum, 2> s;
  for (int i = 0; i < sim.owned(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    s[0].add(p.mass(k));
    s[1].add(p.mass(k) * p.x[k].z());
  }
  dem::ExactSum::reduce(s, sim.comm());
  return {s[0].value(), s[1].value()};
}

// The bed's state under gravity times `factor`; needs a step that recorded its contacts. K0 is
// the ratio of the Bagi sums over a box that holds every grain (the box's volume cancels);
// sigma_v is the equilibrium's f W / (2 A) over the height 2 zc.
OedometerRecord measure_by_gravity(const dem::Simulation& sim, double factor, double weight,
                                   double first_centroid) {
  const dem::SceneConfig& scene = sim.scene();
  const dem::ParticleStore& p = sim.particles();
  double top = 0.0;
  for (int i = 0; i < sim.owned(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  MPI_Allreduce(MPI_IN_PLACE, &top, 1, MPI_DOUBLE, MPI_MAX, sim.comm());
  OedometerRecord r;
  r.time = sim.time();
  r.gravity_factor = factor;
  r.centroid = mass_moment(sim).centroid();
  r.height = 2.0 * r.centroid;
  dem::RegularGrid grid;
  grid.lo = dem::Vec3::Zero();
  grid.hi = dem::Vec3(scene.container.lx, scene.container.ly, top);
  r.bagi = sim.grid_stress(grid)[dem::StressFormula::bagi][0];
  const double area = scene.container.lx * scene.container.ly;
  r.state.vertical_stress = factor * weight / (2.0 * area);
  r.state.horizontal_stress = r.state.vertical_stress * 0.5 * (r.bagi(0, 0) + r.bagi(1, 1)) / r.bagi(2, 2);
  r.state.vertical_strain = dem::centroid_vertical_strain(first_centroid, r.centroid);
  return r;
}

// A gravity state is at rest when its centre of mass moved in the last fifth of the hold by at
// most this share of its settlement since the last state.
constexpr double kRestShare = 0.02;
constexpr double kRestWindow = 0.2;

std::vector<OedometerRecord> run_gravity_oedometer(dem::Simulation& sim, const OedometerOptions& o) {
  const dem::Vec3 g = sim.gravity();
  if (!(g.z() < 0.0) || g.x() != 0.0 || g.y() != 0.0)
    throw Error("oedometric test by gravity: the scene's gravity must point down (-z), not (" +
                std::to_string(g.x()) + ", " + std::to_string(g.y()) + ", " + std::to_string(g.z()) + ")");
  double previous_factor = 1.0;
  for (double f : o.gravity_factors)
    if (!(f > previous_factor))
      throw Error("oedometric test by gravity: the factors must ascend from above 1");
    else
      previous_factor = f;
  const std::size_t floor = sim.wall_index("floor");
  if (sim.walls()[floor].point.z() != 0.0 || sim.walls()[floor].normal != dem::Vec3(0.0, 0.0, 1.0))
    throw Error("oedometric test by gravity: the box's floor is not the plane z = 0");
  const MassMoment bed = mass_moment(sim);
  const double weight = bed.mass * -g.z();
  const long hold = hold_steps(o, sim.time_step());
  const long ramp = std::max(1L, hold / 2), window = std::max(1L, std::lround(kRestWindow * hold));
  const long update = std::max(1L, o.update_every);
  std::vector<OedometerRecord> records;
  sim.request_contacts();
  step(sim, o);
  const double first_centroid = mass_moment(sim).centroid();
  records.push_back(measure_by_gravity(sim, 1.0, weight, first_centroid));
  records.back().at_rest = true;
  double from = 1.0;
  for (double to : o.gravity_factors) {
    double window_centroid = 0.0;
    for (long s = 0; s < hold; ++s) {
      // The weight raised linearly over the ramp, in stairs of the servo's update interval.
      if (s % update == 0 && s <= ramp) {
        const double f =
            from + (to - from) * static_cast<double>(std::min(s + update, ramp)) / static_cast<double>(ramp);
        sim.set_gravity(f * g);
      }
      if (s == hold - window) window_centroid = mass_moment(sim).centroid();
      if (s + 1 == hold) sim.request_contacts();
      if (sim.step_count() % kStopCheckEvery == 0) stop_if_requested(sim.comm(), sim.step_count());
      step(sim, o);
    }
    OedometerRecord r = measure_by_gravity(sim, to, weight, first_centroid);
    const double settlement = std::abs(records.back().centroid - r.centroid);
    r.at_rest = std::abs(window_centroid - r.centroid) <= kRestShare * settlement;
    records.push_back(r);
    from = to;
  }
  sim.set_gravity(g);
  return records;
}

}  // namespace

std::vector<OedometerRecord> run_oedometer(dem::Simulation& sim, const OedometerOptions& o) {
  return o.loading == OedometerLoading::gravity ? run_gravity_oedometer(sim, o) : run_lid_oedometer(sim, o);
}

long oedometer_steps(const OedometerOptions& o, double dt) {
  if (o.loading == OedometerLoading::gravity)
    return 1 + hold_steps(o, dt) * static_cast<long>(o.gravity_factors.size());
  return 1 + seating_steps(o, dt) + hold_steps(o, dt) * static_cast<long>(o.lid_stresses.size());
}

}  // namespace upgrain::coupling
