#pragma once
// What a DEM-vs-continuum study adds to a scene (docs/study.md): the continua's material
// and discretisation, and the stress formulas to compare.
#include <optional>
#include <string>
#include <vector>

#include "dem/stress/stress_formula.h"
#include "fem/plasticity/cone_matching.h"
#include "upscale/cg/kernel_kind.h"

namespace upgrain::coupling {

// The continua solved beside the elastic column on frictionless rollers, which the study
// always solves (docs/study.md).
enum class ContinuumVariant {
  elastic_friction,  // linear elastic, Coulomb friction at the walls
  drucker_prager,    // Drucker–Prager elastoplastic, Coulomb friction at the walls
};

struct ContinuumOptions {
  double youngs_modulus = 1e8;  // Pa; the stresses of the confined column do not depend on it
  double poisson_ratio = 0.3;   // K0 = nu / (1 - nu)
  // Continuum/material from: measured on the study's bed (calibration), the entries as set, or
  // the first where the calibration's tests can load the bed (automatic).
  enum class MaterialSource { automatic, calibration, entries };
  MaterialSource material_from = MaterialSource::automatic;
  // The entry's value for `material_from`: auto, calibration or entries.
  [[nodiscard]] const char* material_from_entry() const {
    return material_from == MaterialSource::calibration ? "calibration"
           : material_from == MaterialSource::entries   ? "entries"
                                                        : "auto";
  }
  // Resolved by validate_scene: the study calibrates its continua on its bed; or, automatic
  // without it, why not.
  bool calibrate_in_study = false;
  std::string calibration_skipped;
  // Where E and nu came from: empty for the Continuum entries, else the calibrated material
  // file (Continuum/material file, docs/calibration.md) they were read from, or the one the
  // study's own calibration wrote (`calibrated`).
  std::string material_file;
  bool calibrated = false;
  // The entries the material file set (of youngs modulus, poisson ratio, friction angle,
  // dilatancy angle): those take the file's values, the others keep the Continuum entries.
  std::vector<std::string> material_file_entries;
  // Where an entry's value came from, for printouts and reports: "calibration of this bed,
  // <file>", "material file <file>" or "Continuum entry".
  [[nodiscard]] std::string source_of(const std::string& entry) const {
    for (const std::string& e : material_file_entries)
      if (e == entry) return (calibrated ? "calibration of this bed, " : "material file ") + material_file;
    return "Continuum entry";
  }
  unsigned refinements = 1;  // global refinements of the mesh that matches the stress grid
  unsigned degree = 2;       // Q2 reproduces the analytic column exactly
  std::vector<ContinuumVariant> variants = {ContinuumVariant::elastic_friction,
                                            ContinuumVariant::drucker_prager};
  // Mohr–Coulomb strength of the Drucker–Prager continuum.
  double friction_angle_deg = 30.0;
  double dilatancy_angle_deg = 0.0;
  double cohesion = 0.0;  // Pa
  fem::ConeMatching cone_matching = fem::ConeMatching::outer;
  // Continuum/wall friction and floor friction as written: "auto" (the DEM container's
  // coefficients) or a number; validate_scene turns them into the optionals below (empty =
  // auto).
  std::string wall_friction_entry = "auto";
  std::string floor_friction_entry = "auto";
  std::optional<double> wall_friction;
  std::optional<double> floor_friction;
  unsigned load_steps = 1;           // gravity raised in this many steps
  bool staged_construction = false;  // built layer by layer instead
};

// The coarse-grained fields on the study's mesh (docs/coarse-graining.md).
struct CoarseGrainingOptions {
  // Which fields are written; the stress is always evaluated (it is compared).
  bool density = true, velocity = true, stress = true, wall_force_density = true, displacement = true,
       momentum_balance = true;
  upscale::cg::KernelKind kernel = upscale::cg::KernelKind::gaussian;
  double width = 1.0;                 // in mean grain diameters
  bool at_quadrature_points = false;  // else at the mesh's support points
  bool by_differences = false;        // d(rho V)/dt from two states, else from the accelerations
  double sampling_interval = 0.0;     // s between the two states; 0: one time step
  double reference_time = 0.0;        // s: the reference state of the displacement
  [[nodiscard]] bool any() const {
    return density || velocity || stress || wall_force_density || displacement || momentum_balance;
  }
};

struct StudyOptions {
  bool compare_with_continuum = true;
  // DEM formulas set beside the continuum
  std::vector<dem::StressFormula> formulas = {dem::StressFormula::bagi, dem::StressFormula::modified_nicot,
                                              dem::StressFormula::weber};
  ContinuumOptions continuum;
  CoarseGrainingOptions coarse_graining;
};

}  // namespace upgrain::coupling
