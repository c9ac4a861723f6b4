#pragma once
// Independent long-double references for the ellipsoid contact geometry (docs/ellipsoid-contact.md,
// "Verification"): the tests' and the accuracy study's exact answers. Nothing here calls the
// solver.
//  - construct(): places body 2 so that a chosen unit n is a stationary point of f with the
//    value delta. For |delta| below the smallest radius of curvature of B1 - B2 that point is
//    the global minimum (D4), so depth and normal are known by construction.
//  - dense_minimum(): the same minimisation by another algorithm: f on a Fibonacci lattice of
//    the whole sphere, then long-double Newton (finite-difference Hessian in a chart) from the
//    best few lattice points; the lowest wins. Does not rely on D4.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "dem/contact/ellipsoid_geometry.h"

namespace upgrain::dem::reference {

using Real = long double;
using V3 = Eigen::Matrix<Real, 3, 1>;
using M3 = Eigen::Matrix<Real, 3, 3>;

inline V3 widen(const Vec3& v) { return v.cast<Real>(); }

// The rotation of a (double) quaternion evaluated in long double, without normalising it.
inline M3 rotation(const Eigen::Quaterniond& q) {
  const Real w = q.w(), x = q.x(), y = q.y(), z = q.z();
  M3 r;
  r << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return r;
}

struct Body {
  V3 centre;
  M3 rot;
  V3 axes;
  M3 m;  // R diag(a^2, b^2, c^2) R^T
};

inline Body body(const Ellipsoid& e) {
  Body b{widen(e.centre), rotation(e.orientation), widen(e.semi_axes), M3::Zero()};
  b.m = b.rot * b.axes.cwiseAbs2().asDiagonal() * b.rot.transpose();
  return b;
}

// f(n) = n.(c1 - c2) + sqrt(n^T M1 n) + sqrt(n^T M2 n), for unit n.
inline Real f(const Body& b1, const Body& b2, const V3& n) {
  return n.dot(b1.centre - b2.centre) + std::sqrt(n.dot(b1.m * n)) + std::sqrt(n.dot(b2.m * n));
}

// p1 - p2 = d + M1 n/h1 + M2 n/h2 (the support points of 1 along n and of 2 along -n).
inline V3 gap_vector(const Body& b1, const Body& b2, const V3& n) {
  return (b1.centre - b2.centre) + b1.m * n / std::sqrt(n.dot(b1.m * n)) +
         b2.m * n / std::sqrt(n.dot(b2.m * n));
}

// Implicit function of body b at a world point: < 0 inside, 0 on the surface.
inline Real inside(const Body& b, const V3& x) {
  const V3 y = b.rot.transpose() * (x - b.centre);
  return y.cwiseQuotient(b.axes).squaredNorm() - 1;
}

inline void basis(const V3& n, V3& t1, V3& t2) {
  const V3 helper = std::abs(n.x()) < 0.6L ? V3(1, 0, 0) : V3(0, 1, 0);
  t1 = (helper - helper.dot(n) * n).normalized();
  t2 = n.cross(t1);
}

// Body 2's centre such that n is stationary with f(n) = delta (exact in long double):
// p1 = c1 + M1 n/h1, p2 = p1 - delta n, c2 = p2 + M2 n/h2.
inline V3 construct_centre2(const Body& b1, const Body& b2_shape, const V3& n, Real delta) {
  const V3 p1 = b1.centre + b1.m * n / std::sqrt(n.dot(b1.m * n));
  const V3 p2 = p1 - delta * n;
  return p2 + b2_shape.m * n / std::sqrt(n.dot(b2_shape.m * n));
}

struct Minimum {
  V3 n;
  Real f;
};

// Long-double Newton in the chart n(x) = (n0 + x1 t1 + x2 t2)/|...|, re-centred every step;
// analytic gradient t_i.(p1 - p2), Hessian by central differences of that gradient.
inline Minimum refine(const Body& b1, const Body& b2, V3 n) {
  Real fn = f(b1, b2, n);
  for (int it = 0; it < 60; ++it) {
    V3 t1, t2;
    basis(n, t1, t2);
    auto grad = [&](Real x1, Real x2) {
      const V3 raw = n + x1 * t1 + x2 * t2;
      const Real len = raw.norm();
      const V3 m = raw / len;
      const V3 g = gap_vector(b1, b2, m);
      // d m / d x_j = (t_j - m (m.t_j)) / len
      return Eigen::Matrix<Real, 2, 1>(g.dot(t1 - m * m.dot(t1)) / len, g.dot(t2 - m * m.dot(t2)) / len);
    };
    const Eigen::Matrix<Real, 2, 1> g0 = grad(0, 0);
    const Real h = 1e-7L;
    Eigen::Matrix<Real, 2, 2> hess;
    hess.col(0) = (grad(h, 0) - grad(-h, 0)) / (2 * h);
    hess.col(1) = (grad(0, h) - grad(0, -h)) / (2 * h);
    hess = 0.5L * (hess + hess.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<Real, 2, 2>> eig(hess);
    Eigen::Matrix<Real, 2, 1> lam = eig.eigenvalues();
    const Real floor = 1e-6L * (std::abs(lam(1)) + 1e-30L);
    for (int k = 0; k < 2; ++k) lam(k) = std::max(lam(k), floor);
    Eigen::Matrix<Real, 2, 1> step =
        -eig.eigenvectors() * (eig.eigenvectors().transpose() * g0).cwiseQuotient(lam);
    if (step.norm() > 0.3L) step *= 0.3L / step.norm();
    Real alpha = 1;
    bool moved = false;
    for (int k = 0; k < 60; ++k) {
      const V3 trial = (n + alpha * (step(0) * t1 + step(1) * t2)).normalized();
      const Real ft = f(b1, b2, trial);
      if (ft <= fn) {
        n = trial;
        fn = ft;
        moved = true;
        break;
      }
      alpha *= 0.5L;
    }
    if (!moved || alpha * step.norm() < 1e-17L) break;
  }
  return {n, fn};
}

// Global minimum of f over the whole sphere by dense sampling plus refinement.
inline Minimum dense_minimum(const Body& b1, const Body& b2, int lattice = 6000, int starts = 4) {
  std::vector<std::pair<Real, int>> samples(lattice);
  auto point = [&](int i) {
    const Real z = 1 - 2 * (i + 0.5L) / lattice;
    const Real rho = std::sqrt(std::max<Real>(0, 1 - z * z));
    const Real phi = 2.399963229728653322231555506633613853L * i;
    return V3(rho * std::cos(phi), rho * std::sin(phi), z);
  };
  for (int i = 0; i < lattice; ++i) samples[i] = {f(b1, b2, point(i)), i};
  std::sort(samples.begin(), samples.end());
  Minimum best{point(samples[0].second), samples[0].first};
  std::vector<V3> tried;
  for (const auto& s : samples) {
    if (static_cast<int>(tried.size()) >= starts) break;
    const V3 n = point(s.second);
    bool near = false;
    for (const V3& t : tried) near = near || n.dot(t) > 0.995L;
    if (near) continue;
    tried.push_back(n);
    const Minimum m = refine(b1, b2, n);
    if (m.f < best.f || static_cast<int>(tried.size()) == 1) best = m;
  }
  return best;
}

// ---- constructed pairs: a known depth and normal ----------------------------------------

enum class Orientation { random, face_to_face, tip_to_tip };
inline const char* name(Orientation o) {
  return o == Orientation::random ? "random" : o == Orientation::face_to_face ? "face-to-face" : "tip-to-tip";
}

inline Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec3 v;
  do v = Vec3(g(rng), g(rng), g(rng));
  while (v.norm() < 1e-3);
  return v.normalized();
}

inline Eigen::Quaterniond random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
}

// A rotation taking the body axis `axis` onto n, with a random spin about n.
inline Eigen::Quaterniond aligned(std::mt19937_64& rng, const Vec3& axis, const Vec3& n) {
  std::uniform_real_distribution<double> spin(0.0, 2.0 * M_PI);
  return (Eigen::AngleAxisd(spin(rng), n) * Eigen::Quaterniond::FromTwoVectors(axis, n)).normalized();
}

// A pair with a known signed depth: body 2 placed by construct_centre2() around a random normal.
struct ConstructedPair {
  Ellipsoid e1, e2;
  V3 normal;     // exact normal
  Real depth;    // exact depth of the rounded (double) configuration
  double c_min;  // smallest semi-axis of the pair
};

// Shapes `ratio1`, `ratio2` (a : b : c, a = 1) with major semi-axes uniform in [a_min, a_max],
// body 1 at `far_min` to `far_max` from the origin, and depth delta_over_c times the smaller c.
inline ConstructedPair constructed_pair(std::mt19937_64& rng, const Vec3& ratio1, const Vec3& ratio2,
                                        Orientation o, double delta_over_c, double a_min = 1e-3,
                                        double a_max = 2.5e-3, double far_min = 1.5, double far_max = 2.0) {
  std::uniform_real_distribution<double> size(a_min, a_max), far(far_min, far_max);
  ConstructedPair k;
  const Vec3 n = random_unit(rng);
  k.e1.semi_axes = ratio1 * size(rng);
  k.e2.semi_axes = ratio2 * size(rng);
  k.e1.centre = random_unit(rng) * far(rng);
  if (o == Orientation::random) {
    k.e1.orientation = random_rotation(rng);
    k.e2.orientation = random_rotation(rng);
  } else {
    const Vec3 axis = o == Orientation::face_to_face ? Vec3::UnitZ() : Vec3::UnitX();
    k.e1.orientation = aligned(rng, axis, n);
    k.e2.orientation = aligned(rng, axis, -n);
  }
  k.c_min = std::min(k.e1.semi_axes.minCoeff(), k.e2.semi_axes.minCoeff());
  k.normal = widen(n).normalized();
  const Real delta = static_cast<Real>(delta_over_c) * k.c_min;
  const V3 c2 = construct_centre2(body(k.e1), body(k.e2), k.normal, delta);
  k.e2.centre = c2.cast<double>();
  // Rounding c2 to double moves it by e; to first order the depth changes by -n.e (D2), the
  // second-order term is below 1e-30 m.
  k.depth = delta - k.normal.dot(widen(k.e2.centre) - c2);
  return k;
}

inline Real angle(const Vec3& a, const V3& b) {
  const V3 aw = widen(a);
  return std::atan2(aw.cross(b).norm(), aw.dot(b));
}

}  // namespace upgrain::dem::reference
