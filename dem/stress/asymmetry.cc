#include "dem/stress/asymmetry.h"

#include <Eigen/SVD>
#include <limits>

namespace upgrain::dem {

namespace {
double two_norm(const Mat3& m) { return Eigen::JacobiSVD<Mat3>(m).singularValues()(0); }
}  // namespace

double relative_asymmetry_index(const Mat3& s) {
  const Mat3 skew = 0.5 * (s - s.transpose());
  Mat3 sym_off = 0.5 * (s + s.transpose());
  sym_off.diagonal().setZero();
  const double num = two_norm(skew);
  const double den = two_norm(sym_off);
  if (den == 0.0) return num == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return num / den;
}

}  // namespace upgrain::dem
