#pragma once
// What a DEM-vs-continuum study adds to a scene (docs/study.md): the continuum's material
// and discretisation, and the stress formulas to compare.
#include <vector>

#include "dem/stress/stress_formula.h"
#include "upscale/cg/kernel_kind.h"

namespace upgrain::coupling {

struct ContinuumOptions {
  double youngs_modulus = 1e8;  // Pa; the stresses of the confined column do not depend on it
  double poisson_ratio = 0.3;   // K0 = nu / (1 - nu)
  unsigned refinements = 1;     // global refinements of the mesh that matches the stress grid
  unsigned degree = 2;          // Q2 reproduces the analytic column exactly
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
  std::vector<dem::StressFormula> formulas;  // DEM formulas set beside the continuum
  ContinuumOptions continuum;
  CoarseGrainingOptions coarse_graining;
};

}  // namespace upgrain::coupling
