#include "coupling/calibration/calibration_study.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

#include "coupling/calibration/oedometer_run.h"
#include "coupling/calibration/triaxial_run.h"
#include "coupling/dem_run.h"
#include "coupling/run/scene_run.h"
#include "dem/analysis/oedometer.h"
#include "dem/analysis/triaxial.h"
#include "dem/core/error.h"
#include "dem/io/atomic_file.h"
#include "dem/io/json_number.h"
#include "dem/parallel/exchange.h"
#include "dem/scene/fill.h"

namespace upgrain::coupling {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The bed's weight over the box's footprint (Pa): the scale of the tests' stresses; and its
// grains' mean volume-equivalent diameter, d = (6 m / (pi rho))^(1/3), for the inertial number.
// Summed on rank 0 in the order of the ids, so that they are the same bits on any rank count.
struct BedScales {
  double weight_stress = 0.0;
  double mean_diameter = 0.0;
};
BedScales bed_scales(dem::Simulation& sim) {
  const dem::ParticleStore& all = sim.whole_state();
  const dem::SceneConfig& s = sim.scene();
  double sums[2] = {0.0, 0.0};
  if (sim.is_root()) {
    for (std::size_t i = 0; i < all.size(); ++i) {
      sums[0] += all.mass(i);
      sums[1] += std::cbrt(6.0 * all.mass(i) / (std::numbers::pi * s.particles.material.density));
    }
    sums[1] /= static_cast<double>(std::max<std::size_t>(all.size(), 1));
  }
  MPI_Bcast(sums, 2, MPI_DOUBLE, 0, sim.comm());
  return {sums[0] * s.gravity / (s.container.lx * s.container.ly), sums[1]};
}

// A state in which the servo held its target (within kHeldTolerance): the bed is then at rest
// under the lid, not still being pushed into. Only those enter the fit.
constexpr double kHeldTolerance = 0.05;
bool holds_target(const OedometerRecord& r) {
  return r.target > 0.0 && std::abs(r.lid_stress - r.target) <= kHeldTolerance * r.target;
}

std::string number(double v) {
  if (!std::isfinite(v)) return "";
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

std::string path_table(const std::vector<OedometerRecord>& rec,
                       const std::vector<dem::OedometerStep>& steps) {
  std::ostringstream t;
  t << "# Upgrain oedometric test (docs/calibration.md). SI units. State 0: the deposited bed, the lid just "
       "placed; then one state per lid target, at the end of its hold. sigma_v, sigma_h: the bed's mean Bagi "
       "stress (compression positive; sigma_h the mean of xx and yy); vertical_strain from the lid's height "
       "at state 0; held: the lid within 5 % of its target (only held states enter the fit); M, nu, E: the "
       "step "
       "from the previous loaded state (states >= 2)\n"
       "state,time,target,lid_stress,held,height,vertical_strain,sigma_v,sigma_h,K0,M,nu,E\n";
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const OedometerRecord& r = rec[k];
    const dem::OedometerState& s = r.state;
    t << k << ',' << number(r.time) << ',' << number(r.target) << ',' << number(r.lid_stress) << ','
      << (holds_target(r) ? 1 : 0) << ',' << number(r.height) << ',' << number(s.vertical_strain) << ','
      << number(s.vertical_stress) << ',' << number(s.horizontal_stress) << ','
      << number(s.horizontal_stress / s.vertical_stress);
    if (k >= 2 && k - 2 < steps.size()) {
      const dem::OedometerStep& q = steps[k - 2];
      t << ',' << number(q.modulus) << ',' << number(q.poisson) << ',' << number(q.youngs);
    } else {
      t << ",,,";
    }
    t << '\n';
  }
  return t.str();
}

std::string triaxial_table(const std::vector<TriaxialRecord>& rec) {
  std::ostringstream t;
  t << "# Upgrain friction-angle test (docs/calibration.md): triaxial-like compression without gravity. SI "
       "units, compression positive. Record 0: the bed consolidated to sigma_3 by the five servo walls; then "
       "the lid at a constant axial strain rate, the side walls holding sigma_3. axial_strain from the lid's "
       "height at record 0, volumetric_strain = 1 - V/V_0 of the box between the walls; sigma_xx, sigma_yy, "
       "sigma_zz: the sample's mean Bagi stress over that box; sigma_1 = sigma_zz, sigma_3 = (sigma_xx + "
       "sigma_yy)/2; phi = asin((sigma_1 - sigma_3)/(sigma_1 + sigma_3)) in degrees; the walls' normal "
       "stresses over their faces\n"
       "record,time,axial_strain,volumetric_strain,sigma_xx,sigma_yy,sigma_zz,sigma_1,sigma_3,phi,height,"
       "width_x,width_y,lid,wall_x_min,wall_x_max,wall_y_min,wall_y_max\n";
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const TriaxialRecord& r = rec[k];
    const dem::TriaxialState& s = r.state;
    const double sum = s.axial_stress + s.lateral_stress;
    t << k << ',' << number(r.time) << ',' << number(s.axial_strain) << ',' << number(s.volumetric_strain)
      << ',' << number(-r.bagi(0, 0)) << ',' << number(-r.bagi(1, 1)) << ',' << number(-r.bagi(2, 2)) << ','
      << number(s.axial_stress) << ',' << number(s.lateral_stress) << ','
      << (sum > 0.0 ? number(dem::mobilised_friction_angle(s.axial_stress, s.lateral_stress)) : "") << ','
      << number(r.height) << ',' << number(r.width_x) << ',' << number(r.width_y) << ','
      << number(r.lid_stress);
    for (double w : r.side_stress) t << ',' << number(w);
    t << '\n';
  }
  return t.str();
}

// The critical state: the last 30 % of the shearing; the peak's rate ratio: the states within a
// fifteenth of the final strain of the peak (+-0.01 at the default 0.15).
constexpr double kCriticalShare = 0.3;
constexpr double kPeakWindowShare = 1.0 / 15.0;

}  // namespace

int run_calibration_study(const SceneInput& in, MPI_Comm comm,
                          const std::function<void(const Progress&)>& on_progress) {
  const CalibrationOptions& c = in.calibration;
  if (in.scene.contact_law != "hertz-mindlin")
    throw Error("the calibration's servo lid needs Contact/law = hertz-mindlin, not " + in.scene.contact_law +
                " (docs/calibration.md)");
  if (in.scene.container.has_gate() || in.scene.container.opens_side_walls())
    throw Error(
        "the calibration's tests load the bed in its closed box; a scene with a gate or with side walls "
        "that open (Container) is not one (docs/calibration.md)");
  // The oedometer's ring: the side walls get the calibration's friction (a lubricated ring by
  // default), the floor keeps the scene's.
  dem::SceneConfig scene = in.scene;
  for (int w = 1; w < 5; ++w) scene.container.friction[w] = c.side_wall_friction;
  const auto t0 = Clock::now();
  dem::Simulation sim(scene, fill_on_root(scene, comm), comm, engine_options(in));
  // The deposition, as the scene runs it (to its end time or to rest), without output.
  RunControl deposition = in.control;
  deposition.relax_at_end = false;
  deposition.lid = {};
  const RunResult dep = run_scene(sim, deposition, std::nullopt, on_progress);
  const double deposition_seconds = seconds_since(t0);
  const BedScales scales = bed_scales(sim);
  const double sigma_w = scales.weight_stress;
  // Both tests start from the deposited bed: its state is kept for the second.
  const dem::EngineState settled = sim.capture_state();
  OedometerOptions o;
  for (double f : c.lid_stress_factors) o.lid_stresses.push_back(f * sigma_w);
  o.hold_time = c.hold_time;
  o.seating_time = c.seating_time;
  o.gain_factor = c.gain_factor;
  o.max_speed = c.max_speed;
  o.update_every = c.update_every;
  const auto t1 = Clock::now();
  const std::vector<OedometerRecord> rec = run_oedometer(sim, o);
  const double test_seconds = seconds_since(t1);
  // The friction-angle test on the deposited bed, with frictionless walls (lubricated platens
  // and sides: the walls' shear would add to the sample's strength).
  TriaxialOptions x;
  x.confining_stress = c.confining_stress_factor * sigma_w;
  x.strain_rate = c.axial_strain_rate;
  x.final_strain = c.final_axial_strain;
  x.consolidation_time = c.consolidation_time;
  x.gain_factor = c.gain_factor;
  x.max_speed = c.max_speed;
  x.update_every = c.update_every;
  const auto t2 = Clock::now();
  std::vector<TriaxialRecord> shear;
  {
    dem::SceneConfig smooth = scene;
    for (double& f : smooth.container.friction) f = 0.0;
    dem::EngineState start = settled;
    for (dem::PlaneWall& w : start.walls) w.friction = 0.0;
    dem::Simulation tx(smooth, start, comm, sim.options());
    shear = run_triaxial(tx, x);
  }
  const double triaxial_seconds = seconds_since(t2);
  const double inertial = dem::inertial_number(x.strain_rate, scales.mean_diameter,
                                               scene.particles.material.density, x.confining_stress);
  std::vector<dem::OedometerState> loaded, held;
  for (std::size_t k = 1; k < rec.size(); ++k) {
    loaded.push_back(rec[k].state);
    if (holds_target(rec[k])) held.push_back(rec[k].state);
  }
  const double sigma_mean = rec.front().state.vertical_stress;
  const double k0_deposited = rec.front().state.horizontal_stress / sigma_mean;
  // The paths are written whatever the fits make of them: a path without a modulus or a strength
  // is refused after.
  std::vector<dem::OedometerStep> steps;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  dem::ElasticEquivalent eq{nan, nan, nan, nan, nan, nan, nan};
  std::string fit_error;
  try {
    steps = dem::oedometer_steps(loaded);
    if (held.size() < 2)
      throw Error(
          "only " + std::to_string(held.size()) + " of the " + std::to_string(loaded.size()) +
          " targets were held (the lid within 5 % of its target at the end of the hold); a modulus needs "
          "two: lengthen Calibration/hold time or seating time");
    eq = dem::elastic_equivalent(held, sigma_mean);
  } catch (const Error& e) {
    fit_error = e.what();
  }
  dem::FrictionStrength strength{nan, nan, nan, nan, nan, nan, nan, nan, 0};
  std::string strength_error;
  try {
    std::vector<dem::TriaxialState> path;
    for (const TriaxialRecord& r : shear) path.push_back(r.state);
    strength = dem::friction_strength(path, kPeakWindowShare * x.final_strain, kCriticalShare);
  } catch (const Error& e) {
    strength_error = e.what();
  }
  // The continuum's strength: the peak angle with the dilatancy there (not below 0: the
  // continuum's flow rule takes 0 <= psi <= phi), or the critical state's with none.
  const double phi = c.critical_state_strength ? strength.critical_angle : strength.peak_angle;
  const double psi =
      c.critical_state_strength ? 0.0 : std::clamp(strength.peak_dilatancy_angle, 0.0, strength.peak_angle);
  const double jaky = dem::jaky_k0(strength.critical_angle);
  on_rank0(comm, [&] {
    const fs::path folder = fs::path(in.output.folder) / "calibration";
    dem::io::create_folder(folder);
    dem::io::write_text_atomically(folder / "oedometer.csv", path_table(rec, steps));
    dem::io::write_text_atomically(folder / "triaxial.csv", triaxial_table(shear));
    // The headline figures (null without a fit); summary.json also marks the folder as a run's
    // (Output/overwrite), so a refused calibration can be run again over it.
    using dem::io::json_number;
    std::ostringstream j;
    j << "{\n  \"study\": \"calibration\",\n  \"particles\": " << sim.particle_count()
      << ",\n  \"deposition_steps\": " << dep.steps
      << ",\n  \"deposition_wall_time_s\": " << json_number(deposition_seconds)
      << ",\n  \"oedometer_wall_time_s\": " << json_number(test_seconds)
      << ",\n  \"triaxial_wall_time_s\": " << json_number(triaxial_seconds)
      << ",\n  \"bed_mean_vertical_stress_Pa\": " << json_number(sigma_mean)
      << ",\n  \"constrained_modulus_Pa\": " << json_number(eq.modulus)
      << ",\n  \"modulus_exponent\": " << json_number(eq.exponent)
      << ",\n  \"modulus_taken_at_Pa\": " << json_number(eq.modulus_stress)
      << ",\n  \"k0\": " << json_number(eq.k0) << ",\n  \"k0_deposited\": " << json_number(k0_deposited)
      << ",\n  \"youngs_modulus_Pa\": " << json_number(eq.youngs)
      << ",\n  \"poisson_ratio\": " << json_number(eq.poisson)
      << ",\n  \"confining_stress_Pa\": " << json_number(x.confining_stress)
      << ",\n  \"axial_strain_rate_per_s\": " << json_number(x.strain_rate)
      << ",\n  \"inertial_number\": " << json_number(inertial)
      << ",\n  \"peak_friction_angle_deg\": " << json_number(strength.peak_angle)
      << ",\n  \"peak_axial_strain\": " << json_number(strength.peak_strain)
      << ",\n  \"peak_dilatancy_angle_deg\": " << json_number(strength.peak_dilatancy_angle)
      << ",\n  \"critical_friction_angle_deg\": " << json_number(strength.critical_angle)
      << ",\n  \"critical_friction_angle_spread_deg\": " << json_number(strength.critical_spread)
      << ",\n  \"critical_volumetric_rate_ratio\": " << json_number(strength.critical_rate_ratio)
      << ",\n  \"friction_angle_deg\": " << json_number(phi)
      << ",\n  \"dilatancy_angle_deg\": " << json_number(psi) << ",\n  \"continuum_strength\": \""
      << (c.critical_state_strength ? "critical state" : "peak") << "\""
      << ",\n  \"jaky_k0\": " << json_number(jaky) << "\n}\n";
    dem::io::write_text_atomically(fs::path(in.output.folder) / "summary.json", j.str());
    if (!fit_error.empty())
      throw Error("calibration: " + fit_error + "; the path is in " + (folder / "oedometer.csv").string());
    if (!strength_error.empty())
      throw Error("calibration: " + strength_error + "; the path is in " +
                  (folder / "triaxial.csv").string());
    if (!(eq.poisson >= 0.0 && eq.poisson <= 0.499) || !(eq.youngs > 0.0))
      throw Error("calibration: the equivalent elastic material (E = " + number(eq.youngs) +
                  " Pa, nu = " + number(eq.poisson) + " from K0 = " + number(eq.k0) +
                  ") is not one the continuum takes (E > 0, 0 <= nu <= 0.499); see " +
                  (folder / "oedometer.csv").string());
    if (!(phi >= 0.1 && phi <= 89.0))
      throw Error("calibration: the friction angle " + number(phi) +
                  " degrees is not one the continuum takes ([0.1, 89]); see " +
                  (folder / "triaxial.csv").string());
    std::ostringstream m;
    m << "# Upgrain calibrated material (docs/calibration.md) of " << in.source << ": the linear elastic\n"
      << "# material equivalent to its bed in oedometric compression at the bed's mean vertical stress\n"
      << "# sigma_v = " << number(sigma_mean) << " Pa: M = " << number(eq.modulus)
      << " Pa (power law M ~ sigma^" << number(eq.exponent) << " through the held states, taken at "
      << number(eq.modulus_stress) << " Pa), K0 = " << number(eq.k0)
      << " (the deposited bed's: " << number(k0_deposited) << ").\n"
      << "# nu = K0 / (1 + K0), E = M (1 + nu)(1 - 2 nu) / (1 - nu). The path: oedometer.csv.\n"
      << "# Strength from the friction-angle test at sigma_3 = " << number(x.confining_stress)
      << " Pa (triaxial.csv): peak phi = " << number(strength.peak_angle) << " deg at axial strain "
      << number(strength.peak_strain) << " with psi = " << number(strength.peak_dilatancy_angle)
      << " deg; critical state phi = " << number(strength.critical_angle) << " +- "
      << number(strength.critical_spread) << " deg.\n"
      << "# The continuum takes the " << (c.critical_state_strength ? "critical state's" : "peak's")
      << " (Calibration/continuum strength). Jaky's K0 = 1 - sin(phi_cs) = " << number(jaky) << ".\n"
      << "subsection Continuum\n"
      << "  set youngs modulus = " << number(eq.youngs) << "\n"
      << "  set poisson ratio = " << number(eq.poisson) << "\n"
      << "  set friction angle = " << number(phi) << "\n"
      << "  set dilatancy angle = " << number(psi) << "\n"
      << "end\n";
    dem::io::write_text_atomically(folder / "material.prm", m.str());
    std::printf(
        "  calibration: deposition %.1f s (%ld steps%s), oedometric test %.1f s (seating %g s, %zu targets x "
        "%g s), friction-angle test %.1f s\n",
        deposition_seconds, dep.steps, dep.stopped_at_rest ? ", stopped at rest" : "", test_seconds,
        o.seating_time, o.lid_stresses.size(), o.hold_time, triaxial_seconds);
    std::printf("  %-6s %12s %12s %5s %12s %12s %8s %12s %8s %12s\n", "state", "target Pa", "lid Pa", "held",
                "sigma_v Pa", "strain", "K0", "M Pa", "nu", "E Pa");
    for (std::size_t k = 0; k < rec.size(); ++k) {
      const dem::OedometerState& st = rec[k].state;
      std::printf("  %-6zu %12.4g %12.4g %5s %12.4g %12.4e %8.3f", k, rec[k].target, rec[k].lid_stress,
                  holds_target(rec[k]) ? "yes" : "no", st.vertical_stress, st.vertical_strain,
                  st.horizontal_stress / st.vertical_stress);
      if (k >= 2)
        std::printf(" %12.4g %8.3f %12.4g\n", steps[k - 2].modulus, steps[k - 2].poisson,
                    steps[k - 2].youngs);
      else
        std::printf("\n");
    }
    std::printf(
        "  at the bed's mean stress %.4g Pa (fit through the %zu held states): M %.4g Pa (exponent %.3f, "
        "taken at "
        "%.4g Pa), K0 %.3f -> E %.4g Pa, nu %.3f\n",
        sigma_mean, held.size(), eq.modulus, eq.exponent, eq.modulus_stress, eq.k0, eq.youngs, eq.poisson);
    std::printf(
        "  friction angle (sigma_3 %.4g Pa, axial strain rate %g/s, inertial number %.2e%s): peak %.2f deg "
        "at "
        "axial strain %.3f, dilatancy %.2f deg; critical state %.2f +- %.2f deg (%d records, d eps_v/d eps_1 "
        "%.3f)\n",
        x.confining_stress, x.strain_rate, inertial,
        inertial > 1e-3 ? ", above 1e-3: not quite quasi-static" : "", strength.peak_angle,
        strength.peak_strain, strength.peak_dilatancy_angle, strength.critical_angle,
        strength.critical_spread, strength.critical_states, strength.critical_rate_ratio);
    std::printf("  K0: measured %.3f (deposited bed), %.3f (oedometric fit); Jaky 1 - sin phi_cs = %.3f\n",
                k0_deposited, eq.k0, jaky);
    std::printf("  continuum strength (%s): friction angle %.4g deg, dilatancy angle %.4g deg\n",
                c.critical_state_strength ? "critical state" : "peak", phi, psi);
    std::printf("  results: %s/{oedometer.csv,triaxial.csv,material.prm}, %s/summary.json\n", folder.c_str(),
                in.output.folder.c_str());
  });
  return 0;
}

}  // namespace upgrain::coupling
