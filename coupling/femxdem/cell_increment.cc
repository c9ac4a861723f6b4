#include "coupling/femxdem/cell_increment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace upgrain::coupling {

CellFactor upper_triangular_factor(const dem::Mat3& f) {
  if (!f.allFinite()) throw std::invalid_argument("the DEM cell: the deformation gradient is not finite");
  if (!(f.determinant() > 0.0))
    throw std::invalid_argument("the DEM cell: det F = " + std::to_string(f.determinant()) +
                                " <= 0, no deformation of a cell");
  CellFactor c;
  dem::Mat3& q = c.rotation;
  dem::Mat3& r = c.stretch;
  r.setZero();
  for (int j = 0; j < 3; ++j) {
    dem::Vec3 v = f.col(j);
    for (int i = 0; i < j; ++i) {
      r(i, j) = q.col(i).dot(f.col(j));
      v -= r(i, j) * q.col(i);
    }
    r(j, j) = v.norm();
    q.col(j) = v / r(j, j);
  }
  return c;
}

void check_one_tilt(const dem::Mat3& stretch) {
  static constexpr const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      if ((i == kTiltShear && j == kTiltGradient) || stretch(i, j) == 0.0) continue;
      throw std::invalid_argument(
          std::string(
              "the DEM cell deforms by the upper-triangular factor R of F = Q R and holds one tilt, R(x, y) "
              "(plane strain in x-y); this F has R(") +
          names[i] + ", " + names[j] + ") = " + std::to_string(stretch(i, j)) +
          ", which needs a general triclinic cell (planned, docs/femxdem.md)");
    }
}

long increment_steps(const dem::Mat3& increment, const RveOptions& o) {
  const double largest = increment.cwiseAbs().maxCoeff();
  return std::max(static_cast<long>(std::ceil(o.steps_per_unit_strain * largest)), o.min_steps);
}

dem::Mat3 increment_velocity_gradient(const dem::Mat3& from, const dem::Mat3& to, long steps, double dt) {
  const double n = static_cast<double>(steps);
  dem::Mat3 l = dem::Mat3::Zero();
  for (int d = 0; d < 3; ++d) l(d, d) = std::expm1(std::log(to(d, d) / from(d, d)) / n) / dt;
  const int s = kTiltShear, g = kTiltGradient;
  const double a = 1.0 + dt * l(s, s), c = 1.0 + dt * l(g, g);
  double a_n = 1.0, sum = 0.0;  // a^n and sum_k a^(n-1-k) c^k, by the recursion the steps take
  for (long k = 0; k < steps; ++k) {
    sum = a * sum + std::pow(c, static_cast<double>(k));
    a_n *= a;
  }
  l(s, g) = (to(s, g) - a_n * from(s, g)) / (dt * from(g, g) * sum);
  return l;
}

}  // namespace upgrain::coupling
