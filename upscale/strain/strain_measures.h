#pragma once
// Finite-strain measures of a deformation gradient F, and the rate measures of a velocity
// gradient L (Holzapfel 2000, "Nonlinear Solid Mechanics", ch. 2; equation numbers below
// are those of docs/strain.md).
//
// The polar decomposition F = R U = V R comes from the singular value decomposition
// F = P S Q^T (P, Q orthogonal, S = diag(s1, s2, s3) > 0): R = P Q^T, U = Q S Q^T,
// V = P S P^T. This holds for any rotation (no series or iteration in the rotation angle),
// and two-sided Jacobi gives the s_i to an absolute error of round-off times s1 even when F
// is close to singular, where the eigenvalues s_i^2 of C = F^T F would be swamped.
// The Hencky strain ln U = (1/2) ln C takes its principal values from the SVD for finite
// strains and from the eigen-decomposition of C - 1 = 2E (ln s_i = log1p(mu_i)/2) near the
// identity, so that a small strain keeps its relative accuracy; E and e are likewise written
// with the displacement gradient H = F - 1 (strain_measures.cc).
#include <string>

#include "dem/core/types.h"

namespace upgrain::upscale {

using dem::Mat3;
using dem::Vec3;

// F is refused as degenerate when its smallest principal stretch is below this fraction of
// the largest: the cell has been flattened to round-off, and ln U would be dominated by noise.
inline constexpr double kMinStretchRatio = 1e-8;

struct PolarDecomposition {
  bool valid = false;
  std::string reason;
  Mat3 rotation = Mat3::Zero();             // R, proper orthogonal
  Mat3 right_stretch = Mat3::Zero();        // U, symmetric positive definite
  Mat3 left_stretch = Mat3::Zero();         // V = R U R^T
  Vec3 principal_stretches = Vec3::Zero();  // s1 >= s2 >= s3 > 0
};

// Invalid (with the reason and zero fields) when F is not finite, J = det F <= 0 (an
// inverted or collapsed cell: no rotation R with det R = +1 and U positive definite exists),
// or s3 < kMinStretchRatio s1.
PolarDecomposition polar_decomposition(const Mat3& f);

struct StrainMeasures {
  bool valid = false;
  std::string reason;
  double jacobian = 0.0;                   // J = det F (3), volume ratio
  Mat3 right_cauchy_green = Mat3::Zero();  // C = F^T F (3)
  Mat3 left_cauchy_green = Mat3::Zero();   // B = F F^T (3)
  Mat3 green_lagrange = Mat3::Zero();      // E = (C - 1)/2 (4), reference frame
  Mat3 euler_almansi = Mat3::Zero();       // e = (1 - B^-1)/2 (4), current frame
  PolarDecomposition polar;                // R, U, V (5)
  Mat3 hencky_right = Mat3::Zero();        // ln U (6), reference frame
  Mat3 hencky_left = Mat3::Zero();         // ln V, current frame (= R ln U R^T)
  double volumetric_strain = 0.0;          // ln J = tr ln U
  // gamma_eq = sqrt(2 dev(ln V) : dev(ln V)): equals the engineering shear strain gamma in
  // infinitesimal simple shear, 2 asinh(gamma/2) in finite simple shear; sqrt(3) times the
  // von Mises equivalent strain sqrt(2/3 dev : dev).
  double equivalent_shear_strain = 0.0;
};

// All measures of F. Invalid when the polar decomposition is (same reasons); every field is
// then zero, never NaN.
StrainMeasures strain_measures(const Mat3& f);

// The deformation from the previous output to now, F_inc = F_now F_prev^-1, so that
// F_now = F_inc F_prev (both F from the same reference t0). Its measures are the
// incremental strains. Invalid when either is not finite or F_prev is degenerate
// (det F_prev <= 0 or s3 < kMinStretchRatio s1).
struct IncrementalDeformation {
  bool valid = false;
  std::string reason;
  Mat3 gradient = Mat3::Zero();
};
IncrementalDeformation incremental_deformation_gradient(const Mat3& f_now, const Mat3& f_prev);

// The rate of deformation D = sym L = (L + L^T)/2 (7) and the spin W = skew L
// = (L - L^T)/2 (7).
inline Mat3 rate_of_deformation(const Mat3& l) { return 0.5 * (l + l.transpose()); }
inline Mat3 spin(const Mat3& l) { return 0.5 * (l - l.transpose()); }

// sqrt(2 dev(D) : dev(D)), the rate of gamma_eq to first order (engineering shear rate).
double equivalent_shear_rate(const Mat3& l);

// [w]_x, the skew matrix with [w]_x y = w x y (the spin of a rigid rotation at rate w).
inline Mat3 cross_matrix(const Vec3& w) {
  Mat3 m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

}  // namespace upgrain::upscale
