#include "coupling/calibration/calibration_study.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "coupling/calibration/oedometer_run.h"
#include "coupling/dem_run.h"
#include "coupling/run/scene_run.h"
#include "dem/analysis/oedometer.h"
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

// The bed's weight over the box's footprint (Pa): the scale of the lid's targets. Summed on
// rank 0 in the order of the ids, so that the targets are the same bits on any rank count.
double weight_stress(dem::Simulation& sim) {
  const dem::ParticleStore& all = sim.whole_state();
  double mass = 0.0;
  if (sim.is_root())
    for (double inv : all.inv_mass) mass += 1.0 / inv;
  MPI_Bcast(&mass, 1, MPI_DOUBLE, 0, sim.comm());
  const dem::SceneConfig& s = sim.scene();
  return mass * s.gravity / (s.container.lx * s.container.ly);
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

}  // namespace

int run_calibration_study(const SceneInput& in, MPI_Comm comm,
                          const std::function<void(const Progress&)>& on_progress) {
  const CalibrationOptions& c = in.calibration;
  if (in.scene.contact_law != "hertz-mindlin")
    throw Error(in.source + ": the calibration's servo lid needs Contact/law = hertz-mindlin, not " +
                in.scene.contact_law + " (docs/calibration.md)");
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
  const double sigma_w = weight_stress(sim);
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
  std::vector<dem::OedometerState> loaded, held;
  for (std::size_t k = 1; k < rec.size(); ++k) {
    loaded.push_back(rec[k].state);
    if (holds_target(rec[k])) held.push_back(rec[k].state);
  }
  const double sigma_mean = rec.front().state.vertical_stress;
  // The path is written whatever the fit makes of it: a path without a modulus is refused after.
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
  on_rank0(comm, [&] {
    const fs::path folder = fs::path(in.output.folder) / "calibration";
    dem::io::create_folder(folder);
    dem::io::write_text_atomically(folder / "oedometer.csv", path_table(rec, steps));
    // The headline figures (null without a fit); summary.json also marks the folder as a run's
    // (Output/overwrite), so a refused calibration can be run again over it.
    std::ostringstream j;
    j << "{\n  \"study\": \"calibration\",\n  \"particles\": " << sim.particle_count()
      << ",\n  \"deposition_steps\": " << dep.steps
      << ",\n  \"deposition_wall_time_s\": " << dem::io::json_number(deposition_seconds)
      << ",\n  \"oedometer_wall_time_s\": " << dem::io::json_number(test_seconds)
      << ",\n  \"bed_mean_vertical_stress_Pa\": " << dem::io::json_number(sigma_mean)
      << ",\n  \"constrained_modulus_Pa\": " << dem::io::json_number(eq.modulus)
      << ",\n  \"modulus_exponent\": " << dem::io::json_number(eq.exponent)
      << ",\n  \"modulus_taken_at_Pa\": " << dem::io::json_number(eq.modulus_stress)
      << ",\n  \"k0\": " << dem::io::json_number(eq.k0)
      << ",\n  \"youngs_modulus_Pa\": " << dem::io::json_number(eq.youngs)
      << ",\n  \"poisson_ratio\": " << dem::io::json_number(eq.poisson) << "\n}\n";
    dem::io::write_text_atomically(fs::path(in.output.folder) / "summary.json", j.str());
    if (!fit_error.empty())
      throw Error("calibration: " + fit_error + "; the path is in " + (folder / "oedometer.csv").string());
    if (!(eq.poisson >= 0.0 && eq.poisson <= 0.499) || !(eq.youngs > 0.0))
      throw Error("calibration: the equivalent elastic material (E = " + number(eq.youngs) +
                  " Pa, nu = " + number(eq.poisson) + " from K0 = " + number(eq.k0) +
                  ") is not one the continuum takes (E > 0, 0 <= nu <= 0.499); see " +
                  (folder / "oedometer.csv").string());
    std::ostringstream m;
    m << "# Upgrain calibrated material (docs/calibration.md) of " << in.source << ": the linear elastic\n"
      << "# material equivalent to its bed in oedometric compression at the bed's mean vertical stress\n"
      << "# sigma_v = " << number(sigma_mean) << " Pa: M = " << number(eq.modulus)
      << " Pa (power law M ~ sigma^" << number(eq.exponent) << " through the held states, taken at "
      << number(eq.modulus_stress) << " Pa), K0 = " << number(eq.k0)
      << " (the deposited bed's: " << number(rec.front().state.horizontal_stress / sigma_mean) << ").\n"
      << "# nu = K0 / (1 + K0), E = M (1 + nu)(1 - 2 nu) / (1 - nu). The path: oedometer.csv.\n"
      << "subsection Continuum\n"
      << "  set youngs modulus = " << number(eq.youngs) << "\n"
      << "  set poisson ratio = " << number(eq.poisson) << "\n"
      << "end\n";
    dem::io::write_text_atomically(folder / "material.prm", m.str());
    std::printf(
        "  calibration: deposition %.1f s (%ld steps%s), oedometric test %.1f s (seating %g s, %zu targets x "
        "%g s)\n",
        deposition_seconds, dep.steps, dep.stopped_at_rest ? ", stopped at rest" : "", test_seconds,
        o.seating_time, o.lid_stresses.size(), o.hold_time);
    std::printf("  %-6s %12s %12s %5s %12s %12s %8s %12s %8s %12s\n", "state", "target Pa", "lid Pa", "held",
                "sigma_v Pa", "strain", "K0", "M Pa", "nu", "E Pa");
    for (std::size_t k = 0; k < rec.size(); ++k) {
      const dem::OedometerState& s = rec[k].state;
      std::printf("  %-6zu %12.4g %12.4g %5s %12.4g %12.4e %8.3f", k, rec[k].target, rec[k].lid_stress,
                  holds_target(rec[k]) ? "yes" : "no", s.vertical_stress, s.vertical_strain,
                  s.horizontal_stress / s.vertical_stress);
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
    std::printf("  results: %s/{oedometer.csv,material.prm}, %s/summary.json\n", folder.c_str(),
                in.output.folder.c_str());
  });
  return 0;
}

}  // namespace upgrain::coupling
