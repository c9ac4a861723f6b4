#include "coupling/studies/element/element_run.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <span>

#include <Eigen/Eigenvalues>

#include "coupling/studies/element/element_cell.h"
#include "dem/core/cell_motion.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

using Clock = std::chrono::steady_clock;
using dem::CellAxisMode;
using dem::CellMotion;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

dem::CellAxisControl servo(const ElementOptions& o, double target) {
  return cell_servo(target, o.servo_gain, o.max_strain_rate);
}

// The solids' volume and the mean volume-equivalent diameter, summed on rank 0 in id order
// (the fill's), so that they are the same bits on any rank count.
struct Solids {
  double volume = 0.0, mean_diameter = 0.0;
  long count = 0;
};
Solids solids(const dem::ParticleStore& grains, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  double sums[3] = {0.0, 0.0, 0.0};
  if (rank == 0) {
    for (std::size_t i = 0; i < grains.size(); ++i) {
      const double v = grains.volume(i);
      sums[0] += v;
      sums[1] += std::cbrt(6.0 * v / std::numbers::pi);
    }
    sums[1] /= static_cast<double>(std::max<std::size_t>(grains.size(), 1));
    sums[2] = static_cast<double>(grains.size());
  }
  MPI_Bcast(sums, 3, MPI_DOUBLE, 0, comm);
  return {sums[0], sums[1], static_cast<long>(sums[2])};
}

// The principal compressions s1 >= s2 >= s3 of a stress (tension positive, docs/stress.md).
std::array<double, 3> principal_compressions(const dem::Mat3& sigma) {
  const dem::Mat3 symmetric = 0.5 * (sigma + sigma.transpose());
  const Eigen::SelfAdjointEigenSolver<dem::Mat3> e(symmetric, Eigen::EigenvaluesOnly);
  return {-e.eigenvalues()[0], -e.eigenvalues()[1], -e.eigenvalues()[2]};
}

// The mobilised friction angle of the principal compressions: the triaxial test's measure,
// independent of the test's axes (docs/element-tests.md).
double principal_friction_angle(const std::array<double, 3>& s) {
  return s[0] + s[2] > 0.0 ? dem::mobilised_friction_angle(s[0], s[2])
                           : std::numeric_limits<double>::quiet_NaN();
}

// The intermediate principal stress ratio b = (s2 - s3) / (s1 - s3): 0 in triaxial compression.
double intermediate_ratio(const std::array<double, 3>& s) {
  return s[0] > s[2] ? (s[1] - s[2]) / (s[0] - s[2]) : std::numeric_limits<double>::quiet_NaN();
}

// The steady state of one inertial number from the states of its last half: mu the ratio of the
// mean stresses, its spread the standard deviation of the states' ratios.
ShearSteadyState steady_state(std::span<const ShearPathRecord> states, double target, double rate, long steps,
                              double diameter, double density) {
  ShearSteadyState s;
  s.target_inertial_number = target;
  s.shear_rate = rate;
  s.steps = steps;
  double tau = 0.0;
  for (const ShearPathRecord& p : states) {
    tau += p.shear_stress;
    s.normal_stress += p.normal_stress;
    s.mean_stress += p.mean_stress;
    s.mobilised_angle += p.mobilised_angle;
    s.intermediate_ratio += p.intermediate_ratio;
    s.matsuoka_nakai_angle += p.matsuoka_nakai_angle;
    s.solid_fraction += p.solid_fraction;
    s.coordination += p.coordination;
  }
  const double n = static_cast<double>(states.size());
  tau /= n;
  s.normal_stress /= n;
  s.mean_stress /= n;
  s.mobilised_angle /= n;
  s.intermediate_ratio /= n;
  s.matsuoka_nakai_angle /= n;
  s.solid_fraction /= n;
  s.coordination /= n;
  s.friction = tau / s.normal_stress;
  double var = 0.0;
  for (const ShearPathRecord& p : states) {
    const double d = p.shear_stress / p.normal_stress - s.friction;
    var += d * d;
  }
  s.friction_spread = std::sqrt(var / std::max(n - 1.0, 1.0));
  s.inertial_number = dem::inertial_number(rate, diameter, density, s.normal_stress);
  return s;
}

}  // namespace

ElementResult run_element_tests(const dem::SceneConfig& scene_in, dem::ParticleStore grains,
                                const ElementOptions& o, MPI_Comm comm, const dem::EngineOptions& engine,
                                const ProgressReport& on_progress) {
  ElementResult r;
  const Solids solid = solids(grains, comm);
  r.particles = solid.count;
  r.mean_diameter = solid.mean_diameter;
  // No gravity and no walls: the cell's grains alone. The first control squeezes the fill.
  dem::SceneConfig scene = scene_in;
  scene.effects.gravity = false;
  scene.cell = every_axis(servo(o, o.pressures.front()));
  const double dt = scene.time_step;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const double normal_stress = o.pressures.back();
  std::vector<double> shear_rates;
  long shear_total = 0;
  for (double i : o.shear_inertial_numbers) {
    shear_rates.push_back(
        shear_rate_of(i, normal_stress, scene.particles.material.density, solid.mean_diameter));
    shear_total += shear_steps(o, shear_rates.back(), dt);
  }
  const long total = isotropic_steps(o, dt) + triaxial_steps(o, dt) + shear_total;
  ProgressClock clock(rank == 0 ? on_progress : ProgressReport{}, 0);
  long done = 0;
  ElementCell cell(scene, std::move(grains), comm, engine, [&] {
    ++done;
    clock.dynamics(done, total, false, done == total);
  });
  auto coordination = [&](long contacts) { return 2.0 * static_cast<double>(contacts) / solid.count; };

  const auto t1 = Clock::now();
  const IsotropicSchedule plan = isotropic_schedule(o, dt);
  cell.run(steps_of(o.compaction_time, dt), 1);
  for (std::size_t k = 0; k < o.pressures.size(); ++k) {
    IsotropicRecord rec;
    rec.target = o.pressures[k];
    if (k > 0) cell.control(every_axis(servo(o, rec.target)));
    rec.pressure = cell.run(plan.hold, std::max(1L, plan.hold / 4));
    rec.mean_pressure = rec.pressure.mean();
    rec.solid_fraction = solid.volume / cell.volume();
    rec.contacts = cell.sim().diagnostics().particle_contacts;
    rec.coordination = coordination(rec.contacts);
    // The bulk modulus: p of the still cell before and after an isotropic strain step.
    cell.control(still_cell());
    rec.pressure_before = cell.run(plan.still, std::max(1L, plan.still / 2)).mean();
    const double v_before = cell.volume();
    const double rate = -o.volumetric_strain_step / 3.0 / (static_cast<double>(plan.squeeze) * dt);
    cell.control(every_axis(cell_rate(rate)));
    cell.run(plan.squeeze, 1);
    cell.control(still_cell());
    rec.pressure_after = cell.run(plan.still, std::max(1L, plan.still / 2)).mean();
    rec.volumetric_strain = std::log(v_before / cell.volume());
    rec.bulk_modulus = (rec.pressure_after - rec.pressure_before) / rec.volumetric_strain;
    r.isotropic.push_back(rec);
  }
  r.isotropic_seconds = seconds_since(t1);
  // The consolidated state, where the simple shear starts too.
  const dem::EngineState consolidated =
      o.shear_inertial_numbers.empty() ? dem::EngineState{} : cell.sim().capture_state();

  // Drained triaxial compression from the last isotropic state.
  const auto t2 = Clock::now();
  r.confining_pressure = o.pressures.back();
  const std::vector<CellSample> samples = drained_triaxial(
      cell, servo(o, r.confining_pressure), o.axial_strain_rate, triaxial_steps(o, dt), kTriaxialRecords);
  const CellSample& start = samples.front();
  for (const CellSample& c : samples) {
    ElementTriaxialRecord t;
    t.time = c.time;
    t.state = triaxial_state(c, start);
    t.mean_stress = (t.state.axial_stress + 2.0 * t.state.lateral_stress) / 3.0;
    t.deviator = t.state.axial_stress - t.state.lateral_stress;
    t.solid_fraction = solid.volume / c.volume;
    t.coordination = coordination(c.contacts);
    r.triaxial.push_back(t);
  }
  r.triaxial_seconds = seconds_since(t2);

  r.inertial_number = dem::inertial_number(o.axial_strain_rate, r.mean_diameter,
                                           scene.particles.material.density, r.confining_pressure);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  r.strength = {nan, nan, nan, nan, nan, nan, nan, nan, 0};
  try {
    std::vector<dem::TriaxialState> path;
    for (const ElementTriaxialRecord& t : r.triaxial) path.push_back(t.state);
    r.strength =
        dem::friction_strength(path, dem::kPeakWindowShare * o.final_axial_strain, dem::kCriticalShare);
  } catch (const Error& e) {
    r.strength_error = e.what();
  }
  // E50: the secant modulus at half the peak deviator, eps_1 interpolated on the rising path.
  r.e50 = nan;
  const auto peak = std::max_element(r.triaxial.begin(), r.triaxial.end(),
                                     [](const auto& a, const auto& b) { return a.deviator < b.deviator; });
  const double half = 0.5 * peak->deviator;
  for (auto it = r.triaxial.begin(); it != peak && half > 0.0; ++it) {
    const auto next = std::next(it);
    if (it->deviator <= half && next->deviator >= half && next->deviator > it->deviator) {
      const double s = (half - it->deviator) / (next->deviator - it->deviator);
      const double eps = it->state.axial_strain + s * (next->state.axial_strain - it->state.axial_strain);
      if (eps > 0.0) r.e50 = half / eps;
      break;
    }
  }
  const double k_last = r.isotropic.back().bulk_modulus;
  r.poisson_ratio = (3.0 * k_last - r.e50) / (6.0 * k_last);

  // Simple shear at the normal stress P from the consolidated state: x sheared across z
  // (L_xz = gamma_dot), z servo to P at a gain relative to the shear rate, x and y held.
  const auto t3 = Clock::now();
  for (std::size_t n = 0; n < shear_rates.size(); ++n) {
    const double rate = shear_rates[n];
    CellMotion shear;
    shear.axis = {dem::CellAxisControl{CellAxisMode::rate, 0.0, 0.0, 0.0, 0.0},
                  dem::CellAxisControl{CellAxisMode::rate, 0.0, 0.0, 0.0, 0.0},
                  dem::CellAxisControl{CellAxisMode::servo, 0.0, normal_stress,
                                       o.shear_servo_gain * rate / normal_stress, rate}};
    shear.shear.component = {0, 2};
    shear.shear.rate = rate;
    if (n == 0)
      cell.resume(consolidated, shear);
    else
      cell.control(shear);
    const long steps = shear_steps(o, rate, dt), per_state = steps / kShearRecords;
    const std::size_t first = r.shear_path.size();
    for (long k = 1; k <= kShearRecords; ++k) {
      const dem::Mat3 sigma = cell.run_stress(per_state, per_state);
      ShearPathRecord p;
      p.target_inertial_number = o.shear_inertial_numbers[n];
      p.shear_strain = rate * static_cast<double>(k * per_state) * dt;
      p.shear_stress = 0.5 * (sigma(0, 2) + sigma(2, 0));
      p.normal_stress = -sigma(2, 2);
      p.mean_stress = -sigma.trace() / 3.0;
      const std::array<double, 3> principal = principal_compressions(sigma);
      p.mobilised_angle = principal_friction_angle(principal);
      p.intermediate_ratio = intermediate_ratio(principal);
      p.matsuoka_nakai_angle = principal[2] > 0.0
                                   ? dem::matsuoka_nakai_angle(principal[0], principal[1], principal[2])
                                   : std::numeric_limits<double>::quiet_NaN();
      p.solid_fraction = solid.volume / cell.volume();
      p.coordination = coordination(cell.sim().diagnostics().particle_contacts);
      r.shear_path.push_back(p);
    }
    r.shear.push_back(steady_state(std::span(r.shear_path).subspan(first + kShearRecords / 2),
                                   o.shear_inertial_numbers[n], rate, steps, solid.mean_diameter,
                                   scene.particles.material.density));
  }
  r.shear_seconds = seconds_since(t3);
  try {
    std::vector<double> i, mu, phi;
    for (const ShearSteadyState& x : r.shear) {
      i.push_back(x.inertial_number);
      mu.push_back(x.friction);
      phi.push_back(x.solid_fraction);
    }
    if (r.shear.empty()) throw Error("no shear inertial numbers");
    r.phi_of_i = dem::fit_phi_of_i(i, phi);
    r.mu_of_i = dem::fit_mu_of_i(i, mu);
  } catch (const Error& e) {
    r.rheology_error = e.what();
  }
  return r;
}

}  // namespace upgrain::coupling
