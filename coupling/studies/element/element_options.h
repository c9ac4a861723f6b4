#pragma once
// The Element test section of a scene file (docs/element-tests.md): the isotropic and drained
// triaxial compressions and the simple shear at a constant normal stress of `upgrain --study
// element` on a fully periodic cell of the scene's grains (docs/periodic.md, "A cell that
// deforms", "Shear").
#include <algorithm>
#include <cmath>
#include <vector>

namespace upgrain::coupling {

struct ElementOptions {
  // The isotropic compression's targets (Pa), in turn; the last is the triaxial test's sigma_3.
  std::vector<double> pressures = {2.5e4, 5e4, 1e5};
  // Simulated time in which the servo first squeezes the scene's fill into a packing at the
  // first pressure, not recorded.
  double compaction_time = 0.1;  // s
  // Simulated time the servo holds each target before the state is taken.
  double hold_time = 0.05;  // s
  // The servo: L_dd = gain (p_dd - p*) / p*, bounded by max_strain_rate (cell_motion.h).
  double servo_gain = 10.0;       // 1/s
  double max_strain_rate = 10.0;  // 1/s
  // The isotropic strain step of the bulk modulus, eps_v = -dV/V (compression positive).
  double volumetric_strain_step = 1e-4;
  // The drained triaxial compression: eps_1 rate along z and where it ends.
  double axial_strain_rate = 0.5;  // 1/s
  double final_axial_strain = 0.2;
  // Simple shear at the last pressure as normal stress, from the last isotropic state: one
  // steady state per inertial number, in turn (empty: no shear test). Each is sheared by
  // shear_strain; its last half is the steady state.
  std::vector<double> shear_inertial_numbers = {0.003, 0.01, 0.03, 0.1};
  double shear_strain = 2.0;
  // The normal stress's servo during shear, relative to the shear rate: L_gg = gain gamma_dot
  // (p_gg - P) / P, bounded by gamma_dot, so that the cell dilates in the same shear strain at
  // every inertial number.
  double shear_servo_gain = 1.0;
};

// The schedule of the tests in time steps of dt: header-only, for the study's checks too.
inline long steps_of(double time, double dt) { return std::max(1L, std::lround(time / dt)); }

// The phases of one isotropic target: the servo's hold, the still cell before the strain step,
// the step itself, the still cell after it. The step takes a tenth of a hold, each still cell a
// fifth: long enough for the packing's elastic waves to cross the cell many times.
struct IsotropicSchedule {
  long hold = 0, still = 0, squeeze = 0;
  [[nodiscard]] long total() const { return hold + 2 * still + squeeze; }
};
inline IsotropicSchedule isotropic_schedule(const ElementOptions& o, double dt) {
  return {steps_of(o.hold_time, dt), steps_of(0.2 * o.hold_time, dt), steps_of(0.1 * o.hold_time, dt)};
}
inline long isotropic_steps(const ElementOptions& o, double dt) {
  return steps_of(o.compaction_time, dt) +
         static_cast<long>(o.pressures.size()) * isotropic_schedule(o, dt).total();
}

// The states the triaxial path records after its consolidated state.
inline constexpr long kTriaxialRecords = 100;

// The steps of a compression of the cell at the true strain rate `rate` (L_zz = -rate shortens it
// as exp(-rate t), eps_1 = 1 - exp(-rate t)) to `final_strain`, a multiple of `records`.
inline long compression_steps(double final_strain, double rate, double dt, long records) {
  const double time = -std::log1p(-final_strain) / rate;
  return std::max(1L, steps_of(time, dt) / records) * records;
}

// The triaxial compression's steps, a multiple of kTriaxialRecords.
inline long triaxial_steps(const ElementOptions& o, double dt) {
  return compression_steps(o.final_axial_strain, o.axial_strain_rate, dt, kTriaxialRecords);
}

// The states recorded over the shear at one inertial number.
inline constexpr long kShearRecords = 20;

// The shear rate of inertial number I at the normal stress P: gamma_dot = I sqrt(P / rho) / d
// (GDR MiDi 2004, Eur. Phys. J. E 14, 341-365).
inline double shear_rate_of(double inertial_number, double pressure, double density, double diameter) {
  return inertial_number * std::sqrt(pressure / density) / diameter;
}

// The steps of the shear at one rate, a multiple of kShearRecords.
inline long shear_steps(const ElementOptions& o, double rate, double dt) {
  return std::max(1L, steps_of(o.shear_strain / rate, dt) / kShearRecords) * kShearRecords;
}

}  // namespace upgrain::coupling
