#pragma once
// What an accuracy study measures (docs/accuracy.md): the knobs, the values of each, and how
// errors are judged. Read from the scene file's Accuracy section.
#include <array>
#include <string>
#include <vector>

namespace upgrain::coupling {

struct AccuracyOptions {
  // The knobs to turn, by name (accuracy_knobs.h); the others keep the scene's setting.
  std::vector<std::string> knobs = {"time step",
                                    "youngs modulus",
                                    "skin",
                                    "summation",
                                    "ranks",
                                    "shape",
                                    "rotation",
                                    "solver tolerance",
                                    "solver iterations",
                                    "relaxation tolerance",
                                    "grid",
                                    "fem",
                                    "outputs"};
  std::vector<double> time_step_fractions = {0.1, 0.25, 0.5, 1.0};  // of the scene's safe step
  // Young's modulus scaled, with the safe step it allows
  std::vector<double> modulus_factors = {1, 0.1, 0.01};
  std::vector<double> skins = {0.1, 0.2, 0.5};  // neighbour skin, in largest diameters
  std::vector<double> relaxation_tolerances = {1e-5, 1e-7, 1e-9};
  std::vector<double> solver_tolerances = {16, 1e8, 1e10};  // ellipsoid contact solver, in eps x pair size
  std::vector<double> solver_iteration_caps = {30, 4, 2};   // ellipsoid contact solver, Newton steps
  // stress grid cells to try (docs/accuracy.md)
  std::vector<std::array<int, 3>> grids = {{3, 3, 5}, {5, 5, 9}, {7, 7, 13}};
  std::vector<unsigned> fem_degrees = {1, 2, 3};
  std::vector<unsigned> fem_refinements = {0, 1, 2};
  int replicas = 3;         // runs of the reference that differ only in the fill's seed
  double tolerance = 0.01;  // a setting is within tolerance when every change is below this or the noise
};

}  // namespace upgrain::coupling
