#pragma once
// What an accuracy study measures (docs/accuracy.md): the knobs, the values of each, and how
// errors are judged. Read from the scene file's Accuracy section.
#include <array>
#include <string>
#include <vector>

namespace upgrain::coupling {

struct AccuracyOptions {
  // The knobs to turn, by name (accuracy_knobs.h); the others keep the scene's setting.
  std::vector<std::string> knobs;
  std::vector<double> time_step_fractions;  // of the scene's safe step
  std::vector<double> modulus_factors;      // Young's modulus scaled, with the safe step it allows
  std::vector<double> skins;                // neighbour skin, in largest diameters
  std::vector<double> relaxation_tolerances;
  std::vector<double> solver_tolerances;      // ellipsoid contact solver, in eps x pair size
  std::vector<double> solver_iteration_caps;  // ellipsoid contact solver, Newton steps
  std::vector<std::array<int, 3>> grids;      // stress grid cells
  std::vector<unsigned> fem_degrees;
  std::vector<unsigned> fem_refinements;
  int replicas = 3;         // runs of the reference that differ only in the fill's seed
  double tolerance = 0.01;  // a setting is within tolerance when every change is below this or the noise
};

}  // namespace upgrain::coupling
