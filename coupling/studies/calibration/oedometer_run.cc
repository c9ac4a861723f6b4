#include "coupling/studies/calibration/oedometer_run.h"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "coupling/run/lid.h"
#include "coupling/run/run_result.h"
#include "coupling/run/stop_request.h"
#include "coupling/studies/calibration/calibration_options.h"
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
  const long lid = Lid::index(sim);
  OedometerRecord r = stress_below(sim, sim.walls()[static_cast<std::size_t>(lid)].point.z());
  r.time = sim.time();
  r.target = target;
  r.lid_stress = Lid::stress(sim);
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

// The bed's state under gravity times `factor` but its strain; needs a step that recorded its
// contacts. K0 is the ratio of the Bagi sums over a box that holds every grain (the box's volume
// cancels). sigma_v is the equilibrium's: the integral of -sigma_zz over the bed is
// f W zc - sum z_c F_z over the side walls' contacts (F_z the wall's lift on the grain at height
// z_c; the floor's at z = 0 add nothing), over the volume A 2 zc; f W / (2 A) with frictionless
// side walls.
OedometerRecord measure_by_gravity(const dem::Simulation& sim, double factor, double weight) {
  const dem::SceneConfig& scene = sim.scene();
  const double top = highest_grain_top(sim);
  OedometerRecord r;
  r.time = sim.time();
  r.gravity_factor = factor;
  r.centroid = mass_moment(sim).centroid();
  r.height = 2.0 * r.centroid;
  // The side walls' lift and its moment, summed on rank 0 in the contacts' id order.
  double walls[2] = {0.0, 0.0};
  for (const SideWallContact& w : side_wall_contacts(sim)) {
    walls[0] += w.force_on_grain.z();
    walls[1] += w.z * w.force_on_grain.z();
  }
  MPI_Bcast(walls, 2, MPI_DOUBLE, 0, sim.comm());
  r.side_wall_share = walls[0] / (factor * weight);
  dem::RegularGrid grid;
  grid.lo = dem::Vec3::Zero();
  grid.hi = dem::Vec3(scene.container.lx, scene.container.ly, top);
  r.bagi = sim.grid_stress(grid)[dem::StressFormula::bagi][0];
  if (!(r.bagi(2, 2) < 0.0))
    throw Error("oedometric test by gravity: the bed carries no vertical stress (Bagi sigma_zz = " +
                std::to_string(r.bagi(2, 2)) + " Pa): it is not resting on the floor");
  const double area = scene.container.lx * scene.container.ly;
  r.state.vertical_stress = (factor * weight * r.centroid - walls[1]) / (2.0 * area * r.centroid);
  r.state.horizontal_stress = r.state.vertical_stress * 0.5 * (r.bagi(0, 0) + r.bagi(1, 1)) / r.bagi(2, 2);
  return r;
}

// A gravity state is at rest when its centre of mass, sampled kRestSamples times over the last
// fifth of the hold (so that an oscillation of about the window's period is seen), strayed from
// its final height by at most this share of its settlement since the last state.
constexpr double kRestShare = 0.02;
constexpr double kRestWindow = 0.2;
constexpr long kRestSamples = 5;
// The weight rises in at least this many stairs (of Calibration/update interval steps, fewer if
// the ramp is short), each the value at its end.
constexpr long kRampStairs = 10;

// The scene's gravity back on the engine when the test ends, also by an exception.
struct GravityRestored {
  dem::Simulation& sim;
  dem::Vec3 g;
  ~GravityRestored() {
    try {
      sim.set_gravity(g);
    } catch (...) {  // a failed collective while unwinding: the engine is being abandoned anyway
    }
  }
};

std::vector<OedometerRecord> run_gravity_oedometer(dem::Simulation& sim, const OedometerOptions& o) {
  const dem::Vec3 g = sim.gravity();
  if (!(g.z() < 0.0) || g.x() != 0.0 || g.y() != 0.0)
    throw Error("oedometric test by gravity: the scene's gravity must point down (-z), not (" +
                std::to_string(g.x()) + ", " + std::to_string(g.y()) + ", " + std::to_string(g.z()) + ")");
  const std::vector<double>& factors = o.gravity_factors;
  if (const std::string why = gravity_factors_error(factors); !why.empty())
    throw Error("oedometric test by gravity: " + why);
  const std::size_t floor = sim.wall_index("floor");
  if (sim.walls()[floor].point.z() != 0.0 || sim.walls()[floor].normal != dem::Vec3(0.0, 0.0, 1.0))
    throw Error("oedometric test by gravity: the box's floor is not the plane z = 0");
  const MassMoment bed = mass_moment(sim);
  if (!(bed.mass > 0.0)) throw Error("oedometric test by gravity: the box holds no grain");
  const double weight = bed.mass * -g.z();
  const long hold = hold_steps(o, sim.time_step());
  const long ramp = std::max(1L, hold / 2), window = std::max(1L, std::lround(kRestWindow * hold));
  const long stair = std::clamp(ramp / kRampStairs, 1L, std::max(1L, o.update_every));
  const long sample_every = std::max(1L, window / kRestSamples);
  const GravityRestored restore{sim, g};
  // One hold at the bed's own weight first: the bed comes to its state 0 in this box, whose
  // side walls may have lost the friction that held it (a lubricated ring); then one hold per
  // factor. Each hold's centre of mass over its last fifth says whether it came to rest.
  std::vector<std::vector<double>> window_centroids;
  const auto hold_at = [&](double from, double to) {
    std::vector<double> samples;
    for (long s = 0; s < hold; ++s) {
      // The weight raised linearly over the ramp, in stairs.
      if (to != from && s % stair == 0 && s < ramp) {
        const double f =
            from + (to - from) * static_cast<double>(std::min(s + stair, ramp)) / static_cast<double>(ramp);
        sim.set_gravity(f * g);
      }
      if (s >= hold - window && (hold - s) % sample_every == 0)
        samples.push_back(mass_moment(sim).centroid());
      if (s + 1 == hold) sim.request_contacts();
      if (sim.step_count() % kStopCheckEvery == 0) stop_if_requested(sim.comm(), sim.step_count());
      step(sim, o);
    }
    window_centroids.push_back(samples);
    return measure_by_gravity(sim, to, weight);
  };
  std::vector<OedometerRecord> records = {hold_at(1.0, 1.0)};
  double from = 1.0;
  for (double to : factors) {
    records.push_back(hold_at(from, to));
    from = to;
  }
  // At rest: over the last fifth of a hold the centre of mass strayed from its final height by at
  // most kRestShare of the settlement from the state before (state 0: of the first factor's).
  for (std::size_t k = 0; k < records.size(); ++k) {
    const std::size_t a = k == 0 ? 0 : k - 1, b = k == 0 ? std::min<std::size_t>(1, records.size() - 1) : k;
    const double settlement = std::abs(records[a].centroid - records[b].centroid);
    double strayed = 0.0;
    for (double z : window_centroids[k]) strayed = std::max(strayed, std::abs(z - records[k].centroid));
    records[k].at_rest = strayed <= kRestShare * settlement;
    records[k].state.vertical_strain =
        dem::centroid_vertical_strain(records[0].centroid, records[k].centroid);
  }
  return records;
}

}  // namespace

OedometerRecord stress_below(const dem::Simulation& sim, double height) {
  const dem::SceneConfig& scene = sim.scene();
  OedometerRecord r;
  r.height = height;
  dem::RegularGrid grid;
  grid.lo = dem::Vec3::Zero();
  grid.hi = dem::Vec3(scene.container.lx, scene.container.ly, height);
  r.bagi = sim.grid_stress(grid)[dem::StressFormula::bagi][0];
  r.state.vertical_stress = -r.bagi(2, 2);
  r.state.horizontal_stress = -0.5 * (r.bagi(0, 0) + r.bagi(1, 1));
  return r;
}

std::vector<OedometerRecord> run_oedometer(dem::Simulation& sim, const OedometerOptions& o) {
  if (o.loading == OedometerLoading::periodic_cell)
    throw Error("run_oedometer: the periodic cell's oedometric test is run_cell_oedometer()");
  return o.loading == OedometerLoading::gravity ? run_gravity_oedometer(sim, o) : run_lid_oedometer(sim, o);
}

long oedometer_steps(const OedometerOptions& o, double dt) {
  if (o.loading == OedometerLoading::gravity)
    return hold_steps(o, dt) * static_cast<long>(o.gravity_factors.size() + 1);
  return 1 + seating_steps(o, dt) + hold_steps(o, dt) * static_cast<long>(o.lid_stresses.size());
}

}  // namespace upgrain::coupling
