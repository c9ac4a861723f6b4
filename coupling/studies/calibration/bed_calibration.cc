#include "coupling/studies/calibration/bed_calibration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <numbers>
#include <sstream>

#include "coupling/studies/report_format.h"
#include "dem/boundary/container.h"
#include "dem/core/error.h"
#include "dem/core/out_of_memory.h"
#include "dem/files/atomic_file.h"
#include "dem/files/json_number.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The bed's weight over the box's footprint (Pa): the scale of the tests' stresses; and its
// grains' mean volume-equivalent diameter, d = (6 m / (pi rho))^(1/3), for the inertial number.
// Summed on rank 0 in the order of the ids (the state's order), so that they are the same bits
// on any rank count.
struct BedScales {
  double weight_stress = 0.0;
  double mean_diameter = 0.0;
  long particles = 0;
};
BedScales bed_scales(const dem::SceneConfig& s, const dem::EngineState& bed, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  double sums[3] = {0.0, 0.0, 0.0};
  if (rank == 0) {
    const dem::ParticleStore& all = bed.particles;
    for (std::size_t i = 0; i < all.size(); ++i) {
      sums[0] += all.mass(i);
      sums[1] += std::cbrt(6.0 * all.mass(i) / (std::numbers::pi * s.particles.material.density));
    }
    sums[1] /= static_cast<double>(std::max<std::size_t>(all.size(), 1));
    sums[2] = static_cast<double>(all.size());
  }
  MPI_Bcast(sums, 3, MPI_DOUBLE, 0, comm);
  return {sums[0] * s.gravity / (s.container.lx * s.container.ly), sums[1], static_cast<long>(sums[2])};
}

// The bed's state with the walls' friction of a test: the side walls' (x/y min/max), or every
// wall's.
dem::EngineState with_wall_friction(dem::EngineState bed, double side, bool floor_too) {
  for (dem::PlaneWall& w : bed.walls) {
    if (dem::is_side_wall(w.name) || floor_too) w.friction = side;
  }
  return bed;
}

// The first state the fit and the step moduli take: by lid or in the periodic cell, the first
// held target (the step from the unloaded bed includes the seating); by gravity, the bed as it is.
std::size_t first_fitted_state(const OedometerOptions& o) {
  return o.loading == OedometerLoading::gravity ? 0 : 1;
}

// The step that ends at state k (from the state before), or nullptr for a state no step ends at.
const dem::OedometerStep* step_ending_at(const OedometerOptions& o,
                                         const std::vector<dem::OedometerStep>& steps, std::size_t k) {
  const std::size_t first_step = first_fitted_state(o) + 1;
  return k >= first_step && k - first_step < steps.size() ? &steps[k - first_step] : nullptr;
}

std::string path_table(const OedometerOptions& o, const std::vector<OedometerRecord>& rec,
                       const std::vector<dem::OedometerStep>& steps) {
  std::ostringstream t;
  if (o.loading == OedometerLoading::gravity)
    t << "# Upgrain oedometric test by gravity (docs/calibration.md). SI units. State 0: the bed under its "
         "weight W after one hold; then one state per gravity factor f, at the end of its hold. centroid: "
         "the "
         "bed's centre of mass's height zc; side_wall_share: the side walls' lift over f W; vertical_strain "
         "= "
         "3/4 (zc_0 - zc)/zc_0, the mean strain of a uniform column that settles so; sigma_v = (f W zc - sum "
         "z F_z of the side walls' contacts)/(2 A zc), the mean over the height 2 zc by equilibrium (f "
         "W/(2A) "
         "with frictionless side walls); sigma_h = K0 sigma_v with K0 the ratio of the bed's Bagi stresses "
         "(mean of xx and yy over zz); compression positive; at_rest: the centre of mass moved in the last "
         "fifth of the hold by at most 2 % of the settlement from the state before (state 0: of state 1's; "
         "only those enter the fit); M, nu, E: the step from the previous state (states >= 1)\n"
         "state,time,gravity_factor,at_rest,centroid,side_wall_share,vertical_strain,sigma_v,sigma_h,K0,M,nu,"
         "E\n";
  else if (o.loading == OedometerLoading::periodic_cell)
    t << "# Upgrain oedometric test in a periodic cell (docs/calibration.md, \"In a periodic cell\"). SI "
         "units. "
         "State 0: the deposited bed in its box under its weight, its mean Bagi stress from the floor to its "
         "highest point (the cell's height); then its grains without walls or gravity in the fully periodic "
         "cell of that box, x and y still, z servo-controlled to each target in turn, one state at the end "
         "of "
         "each hold: sigma_v = -sigma_zz, sigma_h = -(sigma_xx + sigma_yy)/2 of the cell's Love-Weber stress "
         "over the last quarter of the hold (compression positive); height the cell's; vertical_strain = 1 - "
         "height/height_0; lid_stress empty (no lid); at_rest: sigma_v within 5 % of its target (only those "
         "enter the fit); M, nu, E: the step from the previous loaded state (states >= 2)\n"
         "state,time,target,lid_stress,at_rest,height,vertical_strain,sigma_v,sigma_h,K0,M,nu,E\n";
  else
    t << "# Upgrain oedometric test by a servo lid (docs/calibration.md). SI units. State 0: the deposited "
         "bed, "
         "the lid just placed; then one state per lid target, at the end of its hold. sigma_v, sigma_h: the "
         "bed's mean Bagi stress (compression positive; sigma_h the mean of xx and yy); vertical_strain from "
         "the lid's height at state 0; at_rest: the lid within 5 % of its target (only those enter the fit); "
         "M, nu, E: the step from the previous loaded state (states >= 2)\n"
         "state,time,target,lid_stress,at_rest,height,vertical_strain,sigma_v,sigma_h,K0,M,nu,E\n";
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const OedometerRecord& r = rec[k];
    const dem::OedometerState& s = r.state;
    t << k << ',' << table_number(r.time) << ',';
    if (o.loading == OedometerLoading::gravity)
      t << table_number(r.gravity_factor) << ',' << (r.at_rest ? 1 : 0) << ',' << table_number(r.centroid)
        << ',' << table_number(r.side_wall_share);
    else
      t << table_number(r.target) << ',' << table_number(r.lid_stress) << ',' << (r.at_rest ? 1 : 0) << ','
        << table_number(r.height);
    t << ',' << table_number(s.vertical_strain) << ',' << table_number(s.vertical_stress) << ','
      << table_number(s.horizontal_stress) << ',' << table_number(s.horizontal_stress / s.vertical_stress);
    if (const dem::OedometerStep* q = step_ending_at(o, steps, k)) {
      t << ',' << table_number(q->modulus) << ',' << table_number(q->poisson) << ','
        << table_number(q->youngs);
    } else {
      t << ",,,";
    }
    t << '\n';
  }
  return t.str();
}

std::string triaxial_table(const std::vector<TriaxialRecord>& rec, bool periodic_cell) {
  std::ostringstream t;
  if (periodic_cell)
    t << "# Upgrain friction-angle test in a periodic cell (docs/calibration.md, \"In a periodic cell\"): "
         "drained "
         "triaxial compression of the bed's grains without walls or gravity. SI units, compression positive. "
         "Record 0: the cell consolidated to sigma_3 by its servo on every axis; then z shortened at the "
         "axial "
         "strain rate (L_zz = -rate), x and y holding sigma_3. axial_strain = 1 - height/height_0, "
         "volumetric_strain = 1 - V/V_0 of the cell; sigma_xx, sigma_yy, sigma_zz: the cell's Love-Weber "
         "stress over the steps since the record before; sigma_1 = sigma_zz, sigma_3 = (sigma_xx + "
         "sigma_yy)/2; phi = asin((sigma_1 - sigma_3)/(sigma_1 + sigma_3)) in degrees; height, width_x, "
         "width_y: the cell's lengths; the lid and wall columns empty (none)\n"
         "record,time,axial_strain,volumetric_strain,sigma_xx,sigma_yy,sigma_zz,sigma_1,sigma_3,phi,height,"
         "width_x,width_y,lid,wall_x_min,wall_x_max,wall_y_min,wall_y_max\n";
  else
    t << "# Upgrain friction-angle test (docs/calibration.md): triaxial-like compression without gravity. SI "
         "units, compression positive. Record 0: the bed consolidated to sigma_3 by the five servo walls; "
         "then "
         "the lid at a constant axial strain rate, the side walls holding sigma_3. axial_strain from the "
         "lid's "
         "height at record 0, volumetric_strain = 1 - V/V_0 of the box between the walls; sigma_xx, "
         "sigma_yy, "
         "sigma_zz: the sample's mean Bagi stress over that box; sigma_1 = sigma_zz, sigma_3 = (sigma_xx + "
         "sigma_yy)/2; phi = asin((sigma_1 - sigma_3)/(sigma_1 + sigma_3)) in degrees; the walls' normal "
         "stresses over their faces\n"
         "record,time,axial_strain,volumetric_strain,sigma_xx,sigma_yy,sigma_zz,sigma_1,sigma_3,phi,height,"
         "width_x,width_y,lid,wall_x_min,wall_x_max,wall_y_min,wall_y_max\n";
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const TriaxialRecord& r = rec[k];
    const dem::TriaxialState& s = r.state;
    const double sum = s.axial_stress + s.lateral_stress;
    t << k << ',' << table_number(r.time) << ',' << table_number(s.axial_strain) << ','
      << table_number(s.volumetric_strain) << ',' << table_number(-r.bagi(0, 0)) << ','
      << table_number(-r.bagi(1, 1)) << ',' << table_number(-r.bagi(2, 2)) << ','
      << table_number(s.axial_stress) << ',' << table_number(s.lateral_stress) << ','
      << (sum > 0.0 ? table_number(dem::mobilised_friction_angle(s.axial_stress, s.lateral_stress)) : "")
      << ',' << table_number(r.height) << ',' << table_number(r.width_x) << ',' << table_number(r.width_y)
      << ',' << table_number(r.lid_stress);
    for (double w : r.side_stress) t << ',' << table_number(w);
    t << '\n';
  }
  return t.str();
}

// Both tests between the bed's walls: the oedometer in its ring, whose side walls get the
// calibration's friction (a lubricated ring by default; the floor keeps the scene's), then the
// friction-angle test from the same bed with frictionless walls (lubricated platens and sides:
// the walls' shear would add to the sample's strength).
void calibrate_between_walls(BedCalibration& b, const dem::SceneConfig& scene, const dem::EngineState& bed,
                             const CalibrationOptions& c, MPI_Comm comm, const dem::EngineOptions& engine) {
  const auto t1 = Clock::now();
  {
    dem::SceneConfig ring = scene;
    if (c.lubricate_side_walls)
      for (int w = 1; w < 5; ++w) ring.container.friction[w] = c.side_wall_friction;
    dem::Simulation sim(ring,
                        c.lubricate_side_walls ? with_wall_friction(bed, c.side_wall_friction, false) : bed,
                        comm, engine);
    b.path = allocating("the oedometric test's path", [&] { return run_oedometer(sim, b.oedometer); });
  }
  b.oedometer_seconds = seconds_since(t1);
  const auto t2 = Clock::now();
  {
    dem::SceneConfig smooth = scene;
    for (double& f : smooth.container.friction) f = 0.0;
    dem::Simulation tx(smooth, with_wall_friction(bed, 0.0, true), comm, engine);
    b.shear = allocating("the friction-angle test's path", [&] { return run_triaxial(tx, b.triaxial); });
  }
  b.triaxial_seconds = seconds_since(t2);
}

// Both tests on the bed's grains without walls, each from the same bed (periodic_cell_tests.h).
void calibrate_in_periodic_cell(BedCalibration& b, const dem::SceneConfig& scene, const dem::EngineState& bed,
                                const CellServo& servo, MPI_Comm comm, const dem::EngineOptions& engine) {
  const auto t1 = Clock::now();
  const OedometerRecord deposited = deposited_state(scene, bed, comm, engine);
  b.path = allocating("the oedometric test's path", [&] {
    return run_cell_oedometer(scene, bed, deposited, b.oedometer, servo, comm, engine);
  });
  b.oedometer_seconds = seconds_since(t1);
  const auto t2 = Clock::now();
  b.shear = allocating("the friction-angle test's path", [&] {
    return run_cell_triaxial(scene, bed, deposited.height, b.triaxial, servo, comm, engine);
  });
  b.triaxial_seconds = seconds_since(t2);
}

}  // namespace

std::string_view loading_name(OedometerLoading l) {
  switch (l) {
    case OedometerLoading::gravity:
      return "gravity";
    case OedometerLoading::lid:
      return "lid";
    case OedometerLoading::periodic_cell:
      break;
  }
  return "periodic cell";
}

std::string BedCalibration::material_error(const fs::path& folder) const {
  if (!fit_error.empty()) return fit_error + "; the path is in " + (folder / "oedometer.csv").string();
  if (!strength_error.empty())
    return strength_error + "; the path is in " + (folder / "triaxial.csv").string();
  if (!(elastic.poisson >= 0.0 && elastic.poisson <= 0.499) || !(elastic.youngs > 0.0))
    return "the equivalent elastic material (E = " + table_number(elastic.youngs) +
           " Pa, nu = " + table_number(elastic.poisson) + " from K0 = " + table_number(elastic.k0) +
           ") is not one the continuum takes (E > 0, 0 <= nu <= 0.499); see " +
           (folder / "oedometer.csv").string();
  if (!(friction_angle >= 0.1 && friction_angle <= 89.0))
    return "the friction angle " + table_number(friction_angle) +
           " degrees is not one the continuum takes ([0.1, 89]); see " + (folder / "triaxial.csv").string();
  return "";
}

BedCalibration calibrate_bed(const dem::SceneConfig& scene, const dem::EngineState& bed,
                             const CalibrationOptions& c, const CellServo& cell_servo, MPI_Comm comm,
                             const dem::EngineOptions& engine, const ProgressReport& on_progress) {
  BedCalibration b;
  const BedScales scales = bed_scales(scene, bed, comm);
  b.particles = scales.particles;
  b.weight_stress = scales.weight_stress;
  b.critical_state_strength = c.critical_state_strength;
  OedometerOptions& o = b.oedometer;
  o.loading = c.periodic_cell      ? OedometerLoading::periodic_cell
              : c.oedometer_by_lid ? OedometerLoading::lid
                                   : OedometerLoading::gravity;
  o.gravity_factors = c.gravity_factors;
  for (double f : c.lid_stress_factors) o.lid_stresses.push_back(f * scales.weight_stress);
  o.hold_time = c.hold_time;
  o.seating_time = c.seating_time;
  o.gain_factor = c.gain_factor;
  o.max_speed = c.max_speed;
  o.update_every = c.update_every;
  TriaxialOptions& x = b.triaxial;
  x.confining_stress = c.confining_stress_factor * scales.weight_stress;
  x.strain_rate = c.axial_strain_rate;
  x.final_strain = c.final_axial_strain;
  x.consolidation_time = c.consolidation_time;
  x.gain_factor = c.gain_factor;
  x.max_speed = c.max_speed;
  x.update_every = c.update_every;
  // One progress report over both tests.
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const long total = c.periodic_cell
                         ? cell_oedometer_steps(o, scene.time_step) + cell_triaxial_steps(x, scene.time_step)
                         : oedometer_steps(o, scene.time_step) + triaxial_steps(x, scene.time_step);
  ProgressClock clock(rank == 0 ? on_progress : ProgressReport{}, 0);
  long done = 0;
  o.after_step = x.after_step = [&] {
    ++done;
    clock.dynamics(done, total, false, done == total);
  };
  if (c.periodic_cell)
    calibrate_in_periodic_cell(b, scene, bed, cell_servo, comm, engine);
  else
    calibrate_between_walls(b, scene, bed, c, comm, engine);
  o.after_step = x.after_step = nullptr;  // `clock` and `done` end here
  b.inertial_number = dem::inertial_number(x.strain_rate, scales.mean_diameter,
                                           scene.particles.material.density, x.confining_stress);
  // The states from the first fitted one: their steps for the table, those at rest for the fit.
  std::vector<dem::OedometerState> loaded, held;
  for (std::size_t k = first_fitted_state(o); k < b.path.size(); ++k) {
    loaded.push_back(b.path[k].state);
    if (b.path[k].at_rest) held.push_back(b.path[k].state);
  }
  b.held = held.size();
  b.fitted_states = loaded.size();
  b.sigma_mean = b.path.front().state.vertical_stress;
  b.k0_deposited = b.path.front().state.horizontal_stress / b.sigma_mean;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  b.elastic = {nan, nan, nan, nan, nan, nan, nan};
  try {
    b.steps = dem::oedometer_steps(loaded);
    if (held.size() < 2)
      throw Error(
          "only " + std::to_string(held.size()) + " of the " + std::to_string(loaded.size()) +
          (o.loading == OedometerLoading::gravity
               ? " states (the bed under its own weight and each gravity factor) came to rest (the centre "
                 "of mass still moving at the end of the hold); a modulus needs two: lengthen "
                 "Calibration/hold time"
               : std::string(" targets were held (") +
                     (o.loading == OedometerLoading::lid ? "the lid" : "the periodic cell's sigma_zz") +
                     " within 5 % of its target at the end of the hold); a modulus needs two: lengthen "
                     "Calibration/hold time or seating time"));
    b.elastic = dem::elastic_equivalent(held, b.sigma_mean);
  } catch (const Error& e) {
    b.fit_error = e.what();
  }
  b.strength = {nan, nan, nan, nan, nan, nan, nan, nan, 0};
  try {
    std::vector<dem::TriaxialState> path;
    for (const TriaxialRecord& r : b.shear) path.push_back(r.state);
    b.strength = dem::friction_strength(path, dem::kPeakWindowShare * x.final_strain, dem::kCriticalShare);
  } catch (const Error& e) {
    b.strength_error = e.what();
  }
  // The continuum's strength: the peak angle with the dilatancy there (not below 0: the
  // continuum's flow rule takes 0 <= psi <= phi), or the critical state's with none.
  b.friction_angle = c.critical_state_strength ? b.strength.critical_angle : b.strength.peak_angle;
  b.dilatancy_angle = c.critical_state_strength
                          ? 0.0
                          : std::clamp(b.strength.peak_dilatancy_angle, 0.0, b.strength.peak_angle);
  b.jaky_k0 = dem::jaky_k0(b.strength.critical_angle);
  return b;
}

void write_bed_calibration(const fs::path& folder, const std::string& source, const BedCalibration& b) {
  dem::io::create_folder(folder);
  dem::io::write_text_atomically(folder / "oedometer.csv", path_table(b.oedometer, b.path, b.steps));
  dem::io::write_text_atomically(
      folder / "triaxial.csv",
      triaxial_table(b.shear, b.oedometer.loading == OedometerLoading::periodic_cell));
  if (!b.material_error(folder).empty()) return;
  const dem::ElasticEquivalent& eq = b.elastic;
  const dem::FrictionStrength& s = b.strength;
  std::ostringstream m;
  m << "# Upgrain calibrated material (docs/calibration.md) of " << source << ": the linear elastic\n"
    << "# material equivalent to its bed in oedometric compression "
    << (b.oedometer.loading == OedometerLoading::gravity ? "by gravity"
        : b.oedometer.loading == OedometerLoading::lid   ? "by a servo lid"
                                                         : "in a periodic cell (without walls)")
    << " at the bed's mean vertical stress\n"
    << "# sigma_v = " << table_number(b.sigma_mean) << " Pa: M = " << table_number(eq.modulus)
    << " Pa (power law M ~ sigma^" << table_number(eq.exponent) << " through the states at rest, taken at "
    << table_number(eq.modulus_stress) << " Pa), K0 = " << table_number(eq.k0)
    << " (the deposited bed's: " << table_number(b.k0_deposited) << ").\n"
    << "# nu = K0 / (1 + K0), E = M (1 + nu)(1 - 2 nu) / (1 - nu). The path: oedometer.csv.\n"
    << "# Strength from the friction-angle test at sigma_3 = " << table_number(b.triaxial.confining_stress)
    << " Pa (triaxial.csv): peak phi = " << table_number(s.peak_angle) << " deg at axial strain "
    << table_number(s.peak_strain) << " with psi = " << table_number(s.peak_dilatancy_angle)
    << " deg; critical state phi = " << table_number(s.critical_angle) << " +- "
    << table_number(s.critical_spread) << " deg.\n"
    << "# The continuum takes the " << (b.critical_state_strength ? "critical state's" : "peak's")
    << " (Calibration/continuum strength). Jaky's K0 = 1 - sin(phi_cs) = " << table_number(b.jaky_k0) << ".\n"
    << "subsection Continuum\n"
    << "  set youngs modulus = " << table_number(eq.youngs) << "\n"
    << "  set poisson ratio = " << table_number(eq.poisson) << "\n"
    << "  set friction angle = " << table_number(b.friction_angle) << "\n"
    << "  set dilatancy angle = " << table_number(b.dilatancy_angle) << "\n"
    << "end\n";
  dem::io::write_text_atomically(folder / "material.prm", m.str());
}

std::string bed_calibration_json(const BedCalibration& b) {
  using dem::io::json_number;
  const dem::ElasticEquivalent& eq = b.elastic;
  const dem::FrictionStrength& s = b.strength;
  std::ostringstream j;
  j << "  \"oedometer_loading\": \"" << loading_name(b.oedometer.loading) << "\""
    << ",\n  \"oedometer_wall_time_s\": " << json_number(b.oedometer_seconds)
    << ",\n  \"triaxial_wall_time_s\": " << json_number(b.triaxial_seconds)
    << ",\n  \"weight_stress_Pa\": " << json_number(b.weight_stress)
    << ",\n  \"bed_mean_vertical_stress_Pa\": " << json_number(b.sigma_mean)
    << ",\n  \"constrained_modulus_Pa\": " << json_number(eq.modulus)
    << ",\n  \"modulus_exponent\": " << json_number(eq.exponent)
    << ",\n  \"modulus_taken_at_Pa\": " << json_number(eq.modulus_stress)
    << ",\n  \"k0\": " << json_number(eq.k0) << ",\n  \"k0_deposited\": " << json_number(b.k0_deposited)
    << ",\n  \"youngs_modulus_Pa\": " << json_number(eq.youngs)
    << ",\n  \"poisson_ratio\": " << json_number(eq.poisson)
    << ",\n  \"confining_stress_Pa\": " << json_number(b.triaxial.confining_stress)
    << ",\n  \"axial_strain_rate_per_s\": " << json_number(b.triaxial.strain_rate)
    << ",\n  \"inertial_number\": " << json_number(b.inertial_number)
    << ",\n  \"peak_friction_angle_deg\": " << json_number(s.peak_angle)
    << ",\n  \"peak_axial_strain\": " << json_number(s.peak_strain)
    << ",\n  \"peak_dilatancy_angle_deg\": " << json_number(s.peak_dilatancy_angle)
    << ",\n  \"critical_friction_angle_deg\": " << json_number(s.critical_angle)
    << ",\n  \"critical_friction_angle_spread_deg\": " << json_number(s.critical_spread)
    << ",\n  \"critical_volumetric_rate_ratio\": " << json_number(s.critical_rate_ratio)
    << ",\n  \"friction_angle_deg\": " << json_number(b.friction_angle)
    << ",\n  \"dilatancy_angle_deg\": " << json_number(b.dilatancy_angle) << ",\n  \"continuum_strength\": \""
    << (b.critical_state_strength ? "critical state" : "peak") << "\""
    << ",\n  \"jaky_k0\": " << json_number(b.jaky_k0);
  return j.str();
}

void print_bed_calibration(const BedCalibration& b) {
  const OedometerOptions& o = b.oedometer;
  const dem::ElasticEquivalent& eq = b.elastic;
  const dem::FrictionStrength& s = b.strength;
  const bool by_gravity = o.loading == OedometerLoading::gravity;
  const bool in_cell = o.loading == OedometerLoading::periodic_cell;
  if (by_gravity)
    std::printf("oedometric test by gravity %.1f s (%zu factors x %g s), friction-angle test %.1f s\n",
                b.oedometer_seconds, o.gravity_factors.size(), o.hold_time, b.triaxial_seconds);
  else
    std::printf("oedometric test %s %.1f s (seating %g s, %zu targets x %g s), friction-angle test %.1f s\n",
                o.loading == OedometerLoading::lid ? "by lid" : "in a periodic cell", b.oedometer_seconds,
                o.seating_time, o.lid_stresses.size(), o.hold_time, b.triaxial_seconds);
  std::printf("  %-6s %12s %12s %7s %12s %12s %8s %12s %8s %12s\n", "state",
              by_gravity ? "g factor" : "target Pa", by_gravity ? "zc m" : (in_cell ? "height m" : "lid Pa"),
              "at rest", "sigma_v Pa", "strain", "K0", "M Pa", "nu", "E Pa");
  for (std::size_t k = 0; k < b.path.size(); ++k) {
    const OedometerRecord& r = b.path[k];
    const dem::OedometerState& st = r.state;
    std::printf("  %-6zu %12.4g %12.4g %7s %12.4g %12.4e %8.3f", k, by_gravity ? r.gravity_factor : r.target,
                by_gravity ? r.centroid : (in_cell ? r.height : r.lid_stress), r.at_rest ? "yes" : "no",
                st.vertical_stress, st.vertical_strain, st.horizontal_stress / st.vertical_stress);
    if (const dem::OedometerStep* q = step_ending_at(o, b.steps, k))
      std::printf(" %12.4g %8.3f %12.4g\n", q->modulus, q->poisson, q->youngs);
    else
      std::printf("\n");
  }
  std::printf(
      "  at the bed's mean stress %.4g Pa (fit through the %zu states at rest of %zu): M %.4g Pa (exponent "
      "%.3f, taken "
      "at "
      "%.4g Pa), K0 %.3f -> E %.4g Pa, nu %.3f\n",
      b.sigma_mean, b.held, b.fitted_states, eq.modulus, eq.exponent, eq.modulus_stress, eq.k0, eq.youngs,
      eq.poisson);
  std::printf(
      "  friction angle (sigma_3 %.4g Pa, axial strain rate %g/s, inertial number %.2e%s): peak %.2f deg at "
      "axial strain %.3f, dilatancy %.2f deg; critical state %.2f +- %.2f deg (%d records, d eps_v/d eps_1 "
      "%.3f)\n",
      b.triaxial.confining_stress, b.triaxial.strain_rate, b.inertial_number,
      b.inertial_number > 1e-3 ? ", above 1e-3: not quite quasi-static" : "", s.peak_angle, s.peak_strain,
      s.peak_dilatancy_angle, s.critical_angle, s.critical_spread, s.critical_states, s.critical_rate_ratio);
  std::printf("  K0: measured %.3f (deposited bed), %.3f (oedometric fit); Jaky 1 - sin phi_cs = %.3f\n",
              b.k0_deposited, eq.k0, b.jaky_k0);
  std::printf("  continuum strength (%s): friction angle %.4g deg, dilatancy angle %.4g deg\n",
              b.critical_state_strength ? "critical state" : "peak", b.friction_angle, b.dilatancy_angle);
}

}  // namespace upgrain::coupling
