#include "upscale/strain/strain_measures.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>
#include <cstdio>

namespace upgrain::upscale {

namespace {

std::string format(const char* fmt, double x, double y = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, x, y);
  return buf;
}

// Why F cannot be decomposed, or empty. S from its SVD (descending, >= 0).
std::string degeneracy(const Mat3& f, const Vec3& s) {
  if (!f.allFinite()) return "non-finite deformation gradient";
  const double j = f.determinant();
  if (!(j > 0.0)) return format("J = det F = %.6g <= 0: inverted or collapsed cell", j);
  if (s(2) < kMinStretchRatio * s(0)) {
    return format("near-singular F: smallest/largest principal stretch %.3g < %.3g", s(2) / s(0),
                  kMinStretchRatio);
  }
  return {};
}

// Two-sided Jacobi: singular values to high relative accuracy, P and Q orthogonal to
// round-off for any F.
using Svd = Eigen::JacobiSVD<Mat3>;
Svd full_svd(const Mat3& f) { return Svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV); }

PolarDecomposition polar_from_svd(const Mat3& f, const Svd& svd) {
  PolarDecomposition out;
  const Vec3 s = svd.singularValues();
  out.reason = degeneracy(f, s);
  if (!out.reason.empty()) return out;
  const Mat3& p = svd.matrixU();
  const Mat3& q = svd.matrixV();
  // det P det Q = sign(det F) = +1 once J > 0 and s3 > 0 are established above, so P Q^T is
  // proper without the usual reflection correction (which is for det F < 0, refused here).
  if (p.determinant() * q.determinant() < 0.0) {
    out.reason = "SVD factors of opposite orientation despite J > 0 (round-off in a near-singular F)";
    return out;
  }
  out.valid = true;
  out.rotation = p * q.transpose();
  const Mat3 u = q * s.asDiagonal() * q.transpose();
  const Mat3 v = p * s.asDiagonal() * p.transpose();
  out.right_stretch = 0.5 * (u + u.transpose());
  out.left_stretch = 0.5 * (v + v.transpose());
  out.principal_stretches = s;
  return out;
}

}  // namespace

PolarDecomposition polar_decomposition(const Mat3& f) {
  if (!f.allFinite()) {
    PolarDecomposition out;
    out.reason = "non-finite deformation gradient";
    return out;
  }
  return polar_from_svd(f, full_svd(f));
}

StrainMeasures strain_measures(const Mat3& f) {
  StrainMeasures m;
  if (!f.allFinite()) {
    m.reason = m.polar.reason = "non-finite deformation gradient";
    return m;
  }
  const Svd svd = full_svd(f);
  m.polar = polar_from_svd(f, svd);
  if (!m.polar.valid) {
    m.reason = m.polar.reason;
    return m;
  }
  m.valid = true;
  const Vec3& s = m.polar.principal_stretches;
  const Mat3& p = svd.matrixU();
  const Mat3& q = svd.matrixV();

  m.right_cauchy_green = f.transpose() * f;
  m.left_cauchy_green = f * f.transpose();
  // E = (F^T F - 1)/2 written with the displacement gradient H = F - 1 as (H + H^T + H^T H)/2,
  // so that a small strain is not the difference of two numbers near 1.
  const Mat3 h = f - Mat3::Identity();
  m.green_lagrange = 0.5 * (h + h.transpose() + h.transpose() * h);
  // e = (1 - F^-T F^-1)/2 likewise with h = 1 - F^-1 = F^-1 H: (h + h^T - h^T h)/2, where
  // F^-1 = Q S^-1 P^T is applied to the small H rather than subtracted from 1.
  const Mat3 hc = q * s.cwiseInverse().asDiagonal() * (p.transpose() * h);
  m.euler_almansi = 0.5 * (hc + hc.transpose() - hc.transpose() * hc);

  // Principal log-stretches ln s_i and principal reference directions (columns of n).
  // Near the identity (every eigenvalue mu_i of C - 1 = 2E within +-1/2), from the
  // eigen-decomposition of 2E: ln s_i = log1p(mu_i)/2 keeps the relative accuracy of a small
  // E, which ln of the singular values (each with an absolute round-off error) would lose.
  // Otherwise from the SVD, which keeps a small stretch accurate where 1 + mu_i would not.
  Vec3 log_s;
  Mat3 n;
  const Eigen::SelfAdjointEigenSolver<Mat3> es(2.0 * m.green_lagrange);
  if (es.eigenvalues().cwiseAbs().maxCoeff() <= 0.5) {
    log_s = 0.5 * es.eigenvalues().array().log1p();
    n = es.eigenvectors();
  } else {
    log_s = s.array().log();
    n = q;
  }
  // J from the principal stretches (relative accuracy even for small J); ln J = sum ln s_i.
  m.jacobian = s.prod();
  m.volumetric_strain = log_s.sum();
  // ln U = N ln S N^T (= ln C / 2), ln V = R ln U R^T (= P ln S P^T).
  const Mat3 lu = n * log_s.asDiagonal() * n.transpose();
  const Mat3 lv = m.polar.rotation * lu * m.polar.rotation.transpose();
  m.hencky_right = 0.5 * (lu + lu.transpose());
  m.hencky_left = 0.5 * (lv + lv.transpose());
  // dev(ln V) : dev(ln V) from the principal values (ln U and ln V share them).
  const Vec3 dev = log_s.array() - log_s.mean();
  m.equivalent_shear_strain = std::sqrt(2.0 * dev.squaredNorm());
  return m;
}

IncrementalDeformation incremental_deformation_gradient(const Mat3& f_now, const Mat3& f_prev) {
  IncrementalDeformation out;
  if (!f_now.allFinite()) {
    out.reason = "non-finite current deformation gradient";
    return out;
  }
  if (!f_prev.allFinite()) {
    out.reason = "non-finite previous deformation gradient";
    return out;
  }
  const Svd svd = full_svd(f_prev);
  const std::string why = degeneracy(f_prev, svd.singularValues());
  if (!why.empty()) {
    out.reason = "previous F: " + why;
    return out;
  }
  out.valid = true;
  // F_now F_prev^-1 with F_prev^-1 = Q S^-1 P^T (S bounded away from 0 by the check above).
  out.gradient =
      f_now * svd.matrixV() * svd.singularValues().cwiseInverse().asDiagonal() * svd.matrixU().transpose();
  return out;
}

double equivalent_shear_rate(const Mat3& l) {
  Mat3 d = rate_of_deformation(l);
  d.diagonal().array() -= d.trace() / 3.0;
  return std::sqrt(2.0 * d.squaredNorm());
}

}  // namespace upgrain::upscale
