#pragma once
// Best-fit (least-squares) affine map of a set of particles: the deformation gradient F
// from reference and current positions, and the velocity gradient L from current positions
// and velocities (Cundall and Strack 1979; Liao, Chang, Young and Chang 1997, "Evaluation
// of strain in granular assemblies", eq. for the "best-fit" strain; docs/strain.md).
//
// Given pairs (a_p, b_p), p = 1..n, the fit minimises
//   sum_p |b_p - (G a_p + c)|^2
// over the 3x3 matrix G and the vector c. About the centroids abar, bbar it decouples:
//   c = bbar - G abar,   G (sum da da^T) = sum db da^T,   da = a_p - abar, db = b_p - bbar,
// i.e. G = (sum db da^T)(sum da da^T)^-1. F = G for (a, b) = (X, x), L = G for
// (a, b) = (x, v). The particle set is whatever the caller passes: for the Lagrangian
// measure, the particles in the cell at the reference time t0.
//
// Numerics: the coordinates are centred before any product is formed, so a cell 2 m from
// the origin is fitted as accurately as one at the origin, and G is solved from the n x 3
// least-squares problem [da_p^T] G^T = [db_p^T] by Householder QR, which does not square
// the condition number as the normal equations would; no inverse is formed.
#include <span>
#include <string>

#include "dem/core/types.h"

namespace upgrain::upscale {

using dem::Mat3;
using dem::Vec3;

// Fewer than 4 points cannot determine a 3-D affine map (12 unknowns, 3 equations each,
// and 4 affinely independent points are the minimum).
inline constexpr int kMinFitPoints = 4;

// Degeneracy test on the centred second moment M = sum da da^T with eigenvalues
// m_min <= m_mid <= m_max: the fit is refused when m_min < kMinSecondMomentRatio m_max,
// i.e. when the thinnest rms extent of the set is below 1e-3 of the widest. Then the set is
// (nearly) coplanar or collinear and G is (nearly) undetermined normal to it: a position
// error of relative size d along that normal would move G by about d / sqrt(m_min/m_max),
// 1000 d at the threshold. A coplanar set gives a ratio of round-off size (3e-29 for a 5 cm
// cell 2 m from the origin).
inline constexpr double kMinSecondMomentRatio = 1e-6;

struct AffineFit {
  bool valid = false;
  std::string reason;               // why not valid; empty when valid
  Mat3 gradient = Mat3::Zero();     // G: F or L; zero when not valid
  Vec3 translation = Vec3::Zero();  // c = bbar - G abar
  Vec3 centroid = Vec3::Zero();     // abar, the centroid of the a (reference) points
  int points = 0;
  // sqrt(m_min / m_max) of the centred second moment: 1 for an isotropic set, 0 for a
  // planar one (see kMinSecondMomentRatio).
  double spread_ratio = 0.0;
  // sqrt(min sum |b - (G a + c)|^2 / n): the non-affine part of the motion. n times its
  // square is Falk and Langer's (1998) D^2_min for this set, taken about the centroid
  // rather than about a central particle.
  double residual_rms = 0.0;
};

// The affine map b ~ G a + c in least squares. Invalid (with the reason, and zero fields)
// when the spans differ in length, hold fewer than kMinFitPoints points, hold a non-finite
// value, or the a points are degenerate (kMinSecondMomentRatio).
AffineFit fit_affine_map(std::span<const Vec3> a, std::span<const Vec3> b);

// F from the positions at the reference time t0 and now: x ~ F X + c.
inline AffineFit fit_deformation_gradient(std::span<const Vec3> reference, std::span<const Vec3> current) {
  return fit_affine_map(reference, current);
}

// L from the current positions and velocities: v ~ L x + v0.
inline AffineFit fit_velocity_gradient(std::span<const Vec3> positions, std::span<const Vec3> velocities) {
  return fit_affine_map(positions, velocities);
}

}  // namespace upgrain::upscale
