// Input checks and the analytic solution's data: plain C++, kept out of the deal.II
// translation unit so that it compiles in a fraction of a second.
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fem/elastic_column.h"

namespace upgrain::fem {

namespace {

void require(bool ok, const char* name, double value, const char* what) {
  if (ok) return;
  std::ostringstream msg;
  msg << "ColumnProblem." << name << " = " << value << ": " << what;
  throw std::invalid_argument(msg.str());
}

void require_positive(const char* name, double value) {
  require(std::isfinite(value) && value > 0.0, name, value, "must be positive and finite");
}

}  // namespace

void validate(const ColumnProblem& p) {
  require_positive("length_x", p.length_x);
  require_positive("length_y", p.length_y);
  require_positive("height", p.height);
  require_positive("density", p.density);
  require_positive("gravity", p.gravity);
  require_positive("youngs_modulus", p.youngs_modulus);
  // Strain energy is positive definite only for -1 < nu < 1/2; at 1/2 lambda is infinite.
  require(std::isfinite(p.poisson_ratio) && p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5, "poisson_ratio",
          p.poisson_ratio, "must lie in (-1, 0.5)");
  const char* cell_names[3] = {"cells[0]", "cells[1]", "cells[2]"};
  for (int d = 0; d < 3; ++d) require(p.cells[d] > 0, cell_names[d], p.cells[d], "must be at least 1");
  require(p.degree >= 1 && p.degree <= 4, "degree", p.degree, "must be 1, 2, 3 or 4");
  // 8^10 times the coarse cells would not fit any machine this runs on; refuse it early.
  require(p.refinements <= 10, "refinements", p.refinements, "must be at most 10");
}

ConfinedColumn analytic_solution(const ColumnProblem& p) {
  return {p.density * p.gravity, p.height, p.youngs_modulus, p.poisson_ratio};
}

}  // namespace upgrain::fem
