#pragma once
// The grid-stress formulas by the names a scene file gives them (docs/stress.md).
#include <string>
#include <utility>
#include <vector>

#include "dem/stress/stress_formula.h"

namespace upgrain::coupling::input {

inline std::vector<std::pair<std::string, dem::StressFormula>> stress_formula_choices() {
  std::vector<std::pair<std::string, dem::StressFormula>> out;
  for (int k = 0; k < dem::kStressFormulaCount; ++k)
    out.emplace_back(std::string(dem::kStressFormulaNames[k]), static_cast<dem::StressFormula>(k));
  return out;
}

}  // namespace upgrain::coupling::input
