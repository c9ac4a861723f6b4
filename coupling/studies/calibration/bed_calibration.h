#pragma once
// The calibration's two element tests on a deposited bed (docs/calibration.md): the oedometric
// test (oedometer_run.h) and the friction-angle test (triaxial_run.h), each started from the same
// state of the bed, and the continuum material they give: E and nu of the linear elastic
// material equivalent to the bed in oedometric compression at its own mean vertical stress, and
// the Drucker–Prager strength phi, psi. The calibration study runs them on a bed it deposits
// (calibration_study.h); the DEM-vs-continuum study on the bed it compares (docs/study.md,
// Continuum/material from).
#include <mpi.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "coupling/input/scene_input.h"
#include "coupling/run/progress_clock.h"
#include "coupling/studies/calibration/calibration_options.h"
#include "coupling/studies/calibration/oedometer_run.h"
#include "coupling/studies/calibration/periodic_cell_tests.h"
#include "coupling/studies/calibration/triaxial_run.h"
#include "dem/analysis/oedometer.h"
#include "dem/analysis/triaxial.h"
#include "dem/engine/engine_state.h"

namespace upgrain::coupling {

struct BedCalibration {
  long particles = 0;
  double weight_stress = 0.0;  // the bed's weight over the box's footprint (Pa)
  OedometerOptions oedometer;
  TriaxialOptions triaxial;
  std::vector<OedometerRecord> path;      // state 0 unloaded, then one per target
  std::vector<dem::OedometerStep> steps;  // between consecutive loaded states
  std::vector<TriaxialRecord> shear;      // the consolidated state, then the shearing
  std::size_t held = 0;                   // states at rest, of those the fit may take (only those enter it)
  std::size_t fitted_states = 0;   // the states the fit may take: by gravity all, by lid the loaded ones
  double sigma_mean = 0.0;         // the bed's mean vertical stress (Pa): where E is taken
  double k0_deposited = 0.0;       // sigma_h / sigma_v of the bed as it was
  double inertial_number = 0.0;    // of the shearing (GDR MiDi 2004)
  dem::ElasticEquivalent elastic;  // NaN without a fit
  dem::FrictionStrength strength;  // NaN without a fit
  double jaky_k0 = 0.0;            // 1 - sin(phi_cs)
  bool critical_state_strength = false;   // Calibration/continuum strength
  double friction_angle = 0.0;            // the continuum's phi (degrees)
  double dilatancy_angle = 0.0;           // and psi, in [0, phi]
  std::string fit_error, strength_error;  // why a fit failed (empty: fitted)
  double oedometer_seconds = 0.0, triaxial_seconds = 0.0;

  // Why the fits do not give a material the continuum takes (E > 0, 0 <= nu <= 0.499,
  // phi in [0.1, 89]), naming the path file in `folder`; empty when they do.
  [[nodiscard]] std::string material_error(const std::filesystem::path& folder) const;
};

// Both tests from `bed` (rank 0's state; the other ranks may pass an empty one) in the box of
// `scene`: the oedometer's side walls get Calibration/side wall friction, the friction-angle
// test's walls none; or, with options.periodic_cell, in the periodic cell of that box under
// `cell_servo` (periodic_cell_tests.h). Collective over `comm`; the result is the same bits on every rank
// and, with the deterministic summation, on every rank count. `on_progress` (rank 0's) hears of both tests'
// steps as one run.
BedCalibration calibrate_bed(const dem::SceneConfig& scene, const dem::EngineState& bed,
                             const CalibrationOptions& options, const CellServo& cell_servo, MPI_Comm comm,
                             const dem::EngineOptions& engine, const ProgressReport& on_progress = {});

// The periodic cell's servo: the element tests' (Element test/servo gain, max strain rate).
inline CellServo cell_servo_of(const SceneInput& in) {
  return {in.element.servo_gain, in.element.max_strain_rate};
}

// "gravity", "lid" or "periodic cell": the oedometric test's loading as summary.json names it.
std::string_view loading_name(OedometerLoading l);

// Writes folder/oedometer.csv and triaxial.csv, and folder/material.prm (the calibrated
// Continuum entries, a scene-file fragment; its header names `source`) when material_error() is
// empty. Rank 0.
void write_bed_calibration(const std::filesystem::path& folder, const std::string& source,
                           const BedCalibration& b);

// The headline figures as JSON object members (`"key": value` lines, comma-separated, without
// braces; null without a fit).
std::string bed_calibration_json(const BedCalibration& b);

// The path and the fitted material on the console. Rank 0.
void print_bed_calibration(const BedCalibration& b);

}  // namespace upgrain::coupling
