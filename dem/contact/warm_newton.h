#pragma once
// The pieces of the force loop's straight-line Newton step for ellipsoid pairs
// (docs/ellipsoid-contact.md, "In the force loop"), written once over lanes T: double for one
// pair, or Pair for two pairs side by side. Every lane of a Pair runs the operations of the
// double code in the same order, so a pair gets the same bits whether it is solved alone or
// beside another. Notation of ellipsoid_geometry.cc: f(n) = n.d + h1 + h2, u = M1 n,
// h1 = sqrt(n.u), v = M2 n, h2 = sqrt(n.v), G = d + u/h1 + v/h2.
#include <cmath>

#include "dem/contact/ellipsoid_geometry.h"
#include "dem/core/lanes.h"

namespace upgrain::dem::warm {

using lanes::Mask;
using lanes::Pair;
using lanes::sign_of;
using lanes::sqrt_of;

// A pair: the six distinct entries of each symmetric shape matrix (xx, yy, zz, xy, xz, yz),
// d = c1 - c2, the round-off scale and the certificate bound (D4).
template <class T>
struct PairLanes {
  T a[6], b[6];
  T d[3];
  T size, certify;
};

// f and its pieces at a unit normal n.
template <class T>
struct PointLanes {
  T n[3], u[3], v[3];
  T h1, h2, f;
};

// The gradient in a tangent basis of n.
template <class T>
struct GradientLanes {
  T r1, r2;  // 1/h1, 1/h2
  T t1[3], t2[3];
  T g1, g2, norm2;
};

inline void load_pair(const PosedEllipsoid& e1, const PosedEllipsoid& e2, const Vec3& d,
                      PairLanes<double>& p) {
  const Mat3& a = e1.shape;
  const Mat3& b = e2.shape;
  const double ea[6] = {a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2)};
  const double eb[6] = {b(0, 0), b(1, 1), b(2, 2), b(0, 1), b(0, 2), b(1, 2)};
  for (int k = 0; k < 6; ++k) {
    p.a[k] = ea[k];
    p.b[k] = eb[k];
  }
  for (int k = 0; k < 3; ++k) p.d[k] = d[k];
  p.size = std::abs(d.x()) + std::abs(d.y()) + std::abs(d.z()) + e1.major + e2.major;
  p.certify = e1.min_radius + e2.min_radius;
}

// u = M1 n, v = M2 n, h = sqrt(n.Mn), f (M symmetric).
template <class T>
[[gnu::always_inline]] inline void evaluate(const PairLanes<T>& p, PointLanes<T>& q) {
  const T x = q.n[0], y = q.n[1], z = q.n[2];
  q.u[0] = p.a[0] * x + p.a[3] * y + p.a[4] * z;
  q.u[1] = p.a[3] * x + p.a[1] * y + p.a[5] * z;
  q.u[2] = p.a[4] * x + p.a[5] * y + p.a[2] * z;
  q.v[0] = p.b[0] * x + p.b[3] * y + p.b[4] * z;
  q.v[1] = p.b[3] * x + p.b[1] * y + p.b[5] * z;
  q.v[2] = p.b[4] * x + p.b[5] * y + p.b[2] * z;
  q.h1 = sqrt_of(x * q.u[0] + y * q.u[1] + z * q.u[2]);
  q.h2 = sqrt_of(x * q.v[0] + y * q.v[1] + z * q.v[2]);
  q.f = x * p.d[0] + y * p.d[1] + z * p.d[2] + q.h1 + q.h2;
}

// The gradient G in the tangent basis of n (tangent_basis(): Duff et al. 2017).
template <class T>
[[gnu::always_inline]] inline void gradient(const PairLanes<T>& p, const PointLanes<T>& q,
                                            GradientLanes<T>& g) {
  g.r1 = 1.0 / q.h1;
  g.r2 = 1.0 / q.h2;
  const T gx = p.d[0] + q.u[0] * g.r1 + q.v[0] * g.r2;
  const T gy = p.d[1] + q.u[1] * g.r1 + q.v[1] * g.r2;
  const T gz = p.d[2] + q.u[2] * g.r1 + q.v[2] * g.r2;
  const T nx = q.n[0], ny = q.n[1], nz = q.n[2];
  const T sign = sign_of(nz);
  const T ta = -1.0 / (sign + nz);
  const T tb = nx * ny * ta;
  g.t1[0] = 1.0 + sign * nx * nx * ta;
  g.t1[1] = sign * tb;
  g.t1[2] = -sign * nx;
  g.t2[0] = tb;
  g.t2[1] = sign + ny * ny * ta;
  g.t2[2] = -ny;
  g.g1 = g.t1[0] * gx + g.t1[1] * gy + g.t1[2] * gz;
  g.g2 = g.t2[0] * gx + g.t2[1] * gy + g.t2[2] * gz;
  g.norm2 = g.g1 * g.g1 + g.g2 * g.g2;
}

// The tangent Hessian t_i^T S t_j - (t_i.u)(t_j.u)/h1^3 - (t_i.v)(t_j.v)/h2^3 - f delta_ij with
// S = M1/h1 + M2/h2, and whether it needs no shift: newton_on_sphere()'s test l_min >= kappa =
// 1e-3 (tr H + certify) / 1.001, i.e. H - kappa 1 positive semi-definite (diagonal entries and
// determinant non-negative). Its Newton step x.
template <class T, class Mask>
[[gnu::always_inline]] inline void newton_step(const PairLanes<T>& p, const PointLanes<T>& q,
                                               const GradientLanes<T>& g, Mask& definite, T& x1, T& x2) {
  const T r1 = g.r1, r2 = g.r2;
  const T sxx = p.a[0] * r1 + p.b[0] * r2, syy = p.a[1] * r1 + p.b[1] * r2;
  const T szz = p.a[2] * r1 + p.b[2] * r2, sxy = p.a[3] * r1 + p.b[3] * r2;
  const T sxz = p.a[4] * r1 + p.b[4] * r2, syz = p.a[5] * r1 + p.b[5] * r2;
  const T* t1 = g.t1;
  const T* t2 = g.t2;
  const T s1x = sxx * t1[0] + sxy * t1[1] + sxz * t1[2], s1y = sxy * t1[0] + syy * t1[1] + syz * t1[2];
  const T s1z = sxz * t1[0] + syz * t1[1] + szz * t1[2];
  const T s2x = sxx * t2[0] + sxy * t2[1] + sxz * t2[2], s2y = sxy * t2[0] + syy * t2[1] + syz * t2[2];
  const T s2z = sxz * t2[0] + syz * t2[1] + szz * t2[2];
  const T r1_3 = r1 * r1 * r1, r2_3 = r2 * r2 * r2;
  const T u1 = t1[0] * q.u[0] + t1[1] * q.u[1] + t1[2] * q.u[2],
          u2 = t2[0] * q.u[0] + t2[1] * q.u[1] + t2[2] * q.u[2];
  const T v1 = t1[0] * q.v[0] + t1[1] * q.v[1] + t1[2] * q.v[2],
          v2 = t2[0] * q.v[0] + t2[1] * q.v[1] + t2[2] * q.v[2];
  const T h11 = t1[0] * s1x + t1[1] * s1y + t1[2] * s1z - u1 * u1 * r1_3 - v1 * v1 * r2_3 - q.f;
  const T h22 = t2[0] * s2x + t2[1] * s2y + t2[2] * s2z - u2 * u2 * r1_3 - v2 * v2 * r2_3 - q.f;
  const T h12 = t1[0] * s2x + t1[1] * s2y + t1[2] * s2z - u1 * u2 * r1_3 - v1 * v2 * r2_3;
  const T kappa = 1e-3 * (h11 + h22 + p.certify) / 1.001;
  const T a11 = h11 - kappa, a22 = h22 - kappa;
  definite = (kappa > 0.0) & (a11 >= 0.0) & (a22 >= 0.0) & (a11 * a22 - h12 * h12 >= 0.0);
  const T inv_det = 1.0 / (h11 * h22 - h12 * h12);
  x1 = -(h22 * g.g1 - h12 * g.g2) * inv_det;
  x2 = -(h11 * g.g2 - h12 * g.g1) * inv_det;
}

// n + x1 t1 + x2 t2 back on the sphere: for a step below 1e-6 rad one Newton step for 1/sqrt
// (|n + x|^2 = 1 + |x|^2 <= 1 + 1e-12: its truncation is 1e-24, below the rounding).
template <class T>
[[gnu::always_inline]] inline void small_step(const GradientLanes<T>& g, T x1, T x2, PointLanes<T>& q) {
  T m[3];
  for (int k = 0; k < 3; ++k) m[k] = q.n[k] + x1 * g.t1[k] + x2 * g.t2[k];
  const T norm2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
  const T to_unit = 1.5 - 0.5 * norm2;
  for (int k = 0; k < 3; ++k) q.n[k] = m[k] * to_unit;
}

// The levers from both centres to the mid-point p1 - f n/2 (p1 - c1 = u/h1).
template <class T>
[[gnu::always_inline]] inline void levers(const PairLanes<T>& p, const PointLanes<T>& q, T lever1[3],
                                          T lever2[3]) {
  const T r1 = 1.0 / q.h1;
  for (int k = 0; k < 3; ++k) {
    lever1[k] = q.u[k] * r1 - 0.5 * q.f * q.n[k];
    lever2[k] = lever1[k] + p.d[k];
  }
}

}  // namespace upgrain::dem::warm
