#pragma once
// Symmetric second-order tensors as 6-vectors and fourth-order tensors with the minor
// symmetries as 6x6 matrices, in Mandel's notation (de Souza Neto, Perić & Owen 2008,
// Computational Methods for Plasticity, appendix D; Helnwein 2001, CMAME 190:2753):
//   a = (a11, a22, a33, sqrt2 a12, sqrt2 a13, sqrt2 a23).
// With the sqrt2 on the shear entries, the double contraction A:B is the dot product of
// the vectors and A:D:B is a^T D b, so the tangents below are plain matrix products and
// their symmetry is that of the matrix. Plain Eigen, no deal.II.
#include <Eigen/Core>
#include <cmath>

namespace upgrain::fem {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat3x3 = Eigen::Matrix3d;

namespace mandel {

inline constexpr double sqrt2 = 1.41421356237309504880;

// The second-order identity 1 as a Mandel vector.
inline Vec6 identity() { return (Vec6() << 1, 1, 1, 0, 0, 0).finished(); }

// Symmetric fourth-order identity (a 6x6 identity in Mandel notation) minus 1 (x) 1 / 3: the
// projection onto deviators.
inline Mat6 deviatoric_projector() { return Mat6::Identity() - identity() * identity().transpose() / 3.0; }

inline double trace(const Vec6& a) { return a[0] + a[1] + a[2]; }
inline Vec6 deviator(const Vec6& a) { return a - trace(a) / 3.0 * identity(); }

inline Vec6 from_matrix(const Mat3x3& m) {
  return (Vec6() << m(0, 0), m(1, 1), m(2, 2), sqrt2 * m(0, 1), sqrt2 * m(0, 2), sqrt2 * m(1, 2)).finished();
}
inline Mat3x3 to_matrix(const Vec6& a) {
  Mat3x3 m;
  m << a[0], a[3] / sqrt2, a[4] / sqrt2, a[3] / sqrt2, a[1], a[5] / sqrt2, a[4] / sqrt2, a[5] / sqrt2, a[2];
  return m;
}

}  // namespace mandel

// Isotropic linear elasticity: sigma = K tr(eps) 1 + 2 G dev(eps).
struct Elasticity {
  double shear_modulus = 0.0;  // G = E / (2 (1 + nu))
  double bulk_modulus = 0.0;   // K = E / (3 (1 - 2 nu))

  [[nodiscard]] static Elasticity from_youngs(double youngs_modulus, double poisson_ratio) {
    return {youngs_modulus / (2.0 * (1.0 + poisson_ratio)),
            youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio))};
  }
  [[nodiscard]] Mat6 stiffness() const {
    return 2.0 * shear_modulus * mandel::deviatoric_projector() +
           bulk_modulus * mandel::identity() * mandel::identity().transpose();
  }
  [[nodiscard]] Vec6 stress(const Vec6& strain) const {
    return bulk_modulus * mandel::trace(strain) * mandel::identity() +
           2.0 * shear_modulus * mandel::deviator(strain);
  }
};

}  // namespace upgrain::fem
