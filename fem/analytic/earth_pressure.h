#pragma once
// Coefficients of lateral earth pressure, K = sigma_h / sigma_v, of a cohesionless soil of
// friction angle phi (radians). Plain C++ (docs/fem.md). The elastic K0 = nu / (1 - nu) of
// a laterally confined column is analytic_k0() in confined_column.h.
#include <cmath>

namespace upgrain::fem {

// Rankine's active state (Rankine 1857, Phil. Trans. R. Soc. 147:9): the smallest lateral
// stress a cohesionless soil holds before it fails, K_a = (1 - sin phi) / (1 + sin phi).
inline double rankine_active(double friction_angle) {
  const double s = std::sin(friction_angle);
  return (1.0 - s) / (1.0 + s);
}

// Rankine's passive state, K_p = 1 / K_a.
inline double rankine_passive(double friction_angle) { return 1.0 / rankine_active(friction_angle); }

// Jaky's coefficient at rest (Jaky 1944, J. Soc. Hung. Archit. Eng. 78:355): K0 = 1 - sin phi.
inline double jaky_k0(double friction_angle) { return 1.0 - std::sin(friction_angle); }

}  // namespace upgrain::fem
