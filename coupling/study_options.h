#pragma once
// What a DEM-vs-continuum study adds to a scene (docs/study.md): the continuum's material
// and discretisation, and the stress formulas to compare.
#include <vector>

#include "dem/stress/stress_formula.h"

namespace upgrain::coupling {

struct ContinuumOptions {
  double youngs_modulus = 1e8;  // Pa; the stresses of the confined column do not depend on it
  double poisson_ratio = 0.3;   // K0 = nu / (1 - nu)
  unsigned refinements = 1;     // global refinements of the mesh that matches the stress grid
  unsigned degree = 2;          // Q2 reproduces the analytic column exactly
};

struct StudyOptions {
  bool compare_with_continuum = true;
  std::vector<dem::StressFormula> formulas;  // DEM formulas set beside the continuum
  ContinuumOptions continuum;
};

}  // namespace upgrain::coupling
