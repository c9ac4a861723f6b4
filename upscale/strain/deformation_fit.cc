#include "upscale/strain/deformation_fit.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <cstdio>

namespace upgrain::upscale {

namespace {

AffineFit invalid(std::string reason, int points) {
  AffineFit fit;
  fit.reason = std::move(reason);
  fit.points = points;
  return fit;
}

// The centroid, accumulated about the first point so that the sum holds differences of the
// cell's size, not absolute coordinates (the mean is then accurate to round-off of the
// differences, independent of the distance to the origin).
Vec3 centroid(std::span<const Vec3> pts) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : pts) sum += p - pts[0];
  return pts[0] + sum / static_cast<double>(pts.size());
}

}  // namespace

AffineFit fit_affine_map(std::span<const Vec3> a, std::span<const Vec3> b) {
  const int n = static_cast<int>(a.size());
  if (a.size() != b.size()) {
    return invalid("point counts differ: " + std::to_string(a.size()) + " and " + std::to_string(b.size()),
                   n);
  }
  if (n < kMinFitPoints) {
    return invalid("too few particles: " + std::to_string(n) + " (at least " + std::to_string(kMinFitPoints) +
                       " needed)",
                   n);
  }
  for (int p = 0; p < n; ++p) {
    if (!a[p].allFinite() || !b[p].allFinite()) {
      return invalid("non-finite position or velocity at point " + std::to_string(p), n);
    }
  }

  const Vec3 abar = centroid(a), bbar = centroid(b);
  Eigen::Matrix<double, Eigen::Dynamic, 3> da(n, 3), db(n, 3);
  for (int p = 0; p < n; ++p) {
    da.row(p) = (a[p] - abar).transpose();
    db.row(p) = (b[p] - bbar).transpose();
  }

  // A = QR; the singular values of A (square roots of the eigenvalues of M = A^T A) are
  // those of the 3x3 triangle R, found without forming M.
  const Eigen::HouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 3>> qr(da);
  const Mat3 r = qr.matrixQR().topRows<3>().triangularView<Eigen::Upper>();
  const Vec3 s = Eigen::JacobiSVD<Mat3>(r).singularValues();  // descending
  const double spread = s(0) > 0.0 ? s(2) / s(0) : 0.0;
  if (!(spread * spread >= kMinSecondMomentRatio)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "degenerate reference set: coplanar, collinear or coincident (smallest/largest second "
                  "moment %.3g < %.3g)",
                  spread * spread, kMinSecondMomentRatio);
    AffineFit fit = invalid(buf, n);
    fit.spread_ratio = spread;
    return fit;
  }

  AffineFit fit;
  fit.valid = true;
  fit.points = n;
  fit.spread_ratio = spread;
  fit.centroid = abar;
  fit.gradient = qr.solve(db).transpose();
  fit.translation = bbar - fit.gradient * abar;
  fit.residual_rms = std::sqrt((db - da * fit.gradient.transpose()).squaredNorm() / n);
  return fit;
}

}  // namespace upgrain::upscale
