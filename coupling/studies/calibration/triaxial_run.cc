#include "coupling/studies/calibration/triaxial_run.h"

#include <algorithm>
#include <cmath>

#include "coupling/run/lid.h"
#include "coupling/run/servo_walls.h"
#include "coupling/run/stop_request.h"
#include "dem/boundary/container.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

// The sample's walls: x-, x+, y-, y+ and the lid.
struct SampleWalls {
  std::array<std::size_t, 4> side{};
  std::size_t lid = 0;
};

struct Box {
  double x0, x1, y0, y1, h;
  [[nodiscard]] double volume() const { return (x1 - x0) * (y1 - y0) * h; }
};

Box box_of(const dem::Simulation& sim, const SampleWalls& w) {
  const auto& walls = sim.walls();
  return {walls[w.side[0]].point.x(), walls[w.side[1]].point.x(), walls[w.side[2]].point.y(),
          walls[w.side[3]].point.y(), walls[w.lid].point.z()};
}

// The servo walls with their current faces: a side wall's is its width times the height, the
// lid's the footprint.
std::vector<ServoWall> servo_walls(const dem::Simulation& sim, const SampleWalls& w, double target,
                                   bool with_lid) {
  const Box b = box_of(sim, w);
  std::vector<ServoWall> s = {{w.side[0], target, (b.y1 - b.y0) * b.h},
                              {w.side[1], target, (b.y1 - b.y0) * b.h},
                              {w.side[2], target, (b.x1 - b.x0) * b.h},
                              {w.side[3], target, (b.x1 - b.x0) * b.h}};
  if (with_lid) s.push_back({w.lid, target, (b.x1 - b.x0) * (b.y1 - b.y0)});
  return s;
}

// Needs a step that recorded its contacts.
TriaxialRecord measure(const dem::Simulation& sim, const SampleWalls& w, const Box& first) {
  const Box b = box_of(sim, w);
  const std::vector<dem::Vec3> forces = sim.wall_forces();
  TriaxialRecord r;
  r.time = sim.time();
  r.height = b.h;
  r.width_x = b.x1 - b.x0;
  r.width_y = b.y1 - b.y0;
  r.lid_stress = wall_normal_stress(sim.walls()[w.lid], forces[w.lid], r.width_x * r.width_y);
  for (std::size_t k = 0; k < 4; ++k)
    r.side_stress[k] = wall_normal_stress(sim.walls()[w.side[k]], forces[w.side[k]],
                                          (k < 2 ? r.width_y : r.width_x) * r.height);
  dem::RegularGrid grid;
  grid.lo = dem::Vec3(b.x0, b.y0, 0.0);
  grid.hi = dem::Vec3(b.x1, b.y1, b.h);
  r.bagi = sim.grid_stress(grid)[dem::StressFormula::bagi][0];
  r.state.axial_stress = -r.bagi(2, 2);
  r.state.lateral_stress = -0.5 * (r.bagi(0, 0) + r.bagi(1, 1));
  r.state.axial_strain = (first.h - b.h) / first.h;
  r.state.volumetric_strain = 1.0 - b.volume() / first.volume();
  return r;
}

// The servo's integral term (dem::servo_speed_with_integral): the side walls keep moving as the
// sample contracts or dilates, which a proportional servo holds only with a lag. beta <= alpha/4
// at the default alpha = 0.5: no ringing on a linear spring.
constexpr double kIntegralFactor = 0.1;

// Steps between checks for a stop request (SIGINT, SIGTERM, SIGHUP; one collective each).
constexpr long kStopCheckEvery = 1000;

long consolidation_steps(const TriaxialOptions& o, double dt) {
  return std::max(1L, std::lround(o.consolidation_time / dt));
}
long shearing_steps(const TriaxialOptions& o, double dt) {
  return std::max(static_cast<long>(o.records), std::lround(o.final_strain / o.strain_rate / dt));
}

void step(dem::Simulation& sim, const TriaxialOptions& o) {
  sim.step();
  if (o.after_step) o.after_step();
}

}  // namespace

std::vector<TriaxialRecord> run_triaxial(dem::Simulation& sim, const TriaxialOptions& o) {
  SampleWalls w;
  const std::size_t floor = sim.wall_index("floor");
  if (sim.walls()[floor].point.z() != 0.0 || sim.walls()[floor].normal != dem::Vec3(0.0, 0.0, 1.0))
    throw Error("friction-angle test: the box's floor is not the plane z = 0");
  for (std::size_t k = 0; k < 4; ++k) {
    w.side[k] = sim.wall_index(dem::kSideWallNames[k]);
    if (sim.wall_removed(w.side[k]))
      throw Error(std::string("friction-angle test: the box has no ") + dem::kSideWallNames[k]);
  }
  if (!(o.confining_stress > 0.0) || !(o.strain_rate > 0.0) ||
      !(o.final_strain > 0.0 && o.final_strain < 1.0) || o.records < 2)
    throw Error(
        "friction-angle test: needs a confining stress > 0, a strain rate > 0, a final strain in (0, 1) "
        "and at least 2 records");
  // An element test: no weight, the stress of the walls alone.
  sim.set_gravity(dem::Vec3::Zero());
  w.lid = place_lid(sim, 0.0, 0.0);
  ServoWalls servo(o.gain_factor, o.max_speed, o.update_every, kIntegralFactor);
  // Isotropic consolidation: the five walls hold sigma_3.
  const long consolidation = consolidation_steps(o, sim.time_step());
  for (long s = 0; s < consolidation; ++s) {
    servo.update(sim, servo_walls(sim, w, o.confining_stress, true));
    if (s + 1 == consolidation) sim.request_contacts();
    if (sim.step_count() % kStopCheckEvery == 0) stop_if_requested(sim.comm(), sim.step_count());
    step(sim, o);
  }
  const Box first = box_of(sim, w);
  std::vector<TriaxialRecord> records = {measure(sim, w, first)};
  // The shearing: the lid at the constant speed of the strain rate, the sides at sigma_3.
  sim.set_wall_velocity(w.lid, dem::Vec3(0.0, 0.0, -o.strain_rate * first.h));
  const long total = shearing_steps(o, sim.time_step());
  long done = 0;
  for (int r = 1; r <= o.records; ++r) {
    const long until = total * r / o.records;
    for (; done < until; ++done) {
      servo.update(sim, servo_walls(sim, w, o.confining_stress, false));
      if (done + 1 == until) sim.request_contacts();
      if (sim.step_count() % kStopCheckEvery == 0) stop_if_requested(sim.comm(), sim.step_count());
      step(sim, o);
    }
    records.push_back(measure(sim, w, first));
  }
  return records;
}

long triaxial_steps(const TriaxialOptions& o, double dt) {
  return consolidation_steps(o, dt) + shearing_steps(o, dt);
}

}  // namespace upgrain::coupling
