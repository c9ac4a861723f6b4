#pragma once
// The seven average-stress formulas of Yan and Regueiro's paper (eqs. 1-7, docs/stress.md), by
// name, so outputs can ask for any subset.
#include <array>
#include <optional>
#include <string_view>

namespace upgrain::dem {

enum class StressFormula {
  weber,             // (1) internal contacts, centroid-to-centroid branch
  drescher,          // (2) external contacts, absolute contact point
  bagi,              // (3) internal + external with the boundary-radius-gap branch
  de_saxce,          // (4) all contacts at absolute points + body force and acceleration
  nicot,             // (5) Weber minus the rotational inertial terms
  modified_nicot,    // (6) Bagi minus the rotational inertial terms
  modified_de_saxce  // (7) Bagi minus integral rho y (x) a over the grains
};

inline constexpr int kStressFormulaCount = 7;

inline constexpr std::array<std::string_view, kStressFormulaCount> kStressFormulaNames = {
    "weber", "drescher", "bagi", "de saxce", "nicot", "modified nicot", "modified de saxce"};

inline std::string_view name_of(StressFormula f) { return kStressFormulaNames[static_cast<int>(f)]; }

inline std::optional<StressFormula> stress_formula_from_name(std::string_view name) {
  for (int k = 0; k < kStressFormulaCount; ++k)
    if (kStressFormulaNames[k] == name) return static_cast<StressFormula>(k);
  return std::nullopt;
}

}  // namespace upgrain::dem
