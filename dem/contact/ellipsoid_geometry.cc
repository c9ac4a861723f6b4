// Ellipsoid contact geometry: Newton on the unit sphere of normals for the signed minimum
// translation distance (docs/ellipsoid-contact.md has the derivations cited below as D1-D6).
#include "dem/contact/ellipsoid_geometry.h"

#include "dem/contact/warm_newton.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>

namespace upgrain::dem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kAngleConverged = 1e-6;  // rad: a last step this small is taken unchecked
// Smallest semi-axes (m) for which the solver runs in metres: beyond, 1/h^3 could leave the
// range of doubles.
constexpr double kUnscaledLow = 0x1p-200, kUnscaledHigh = 0x1p200;

// The pair in its own frame (D1): only c1 - c2 enters, so positions far from the origin cost
// no digits. Every quantity of the solver scales with the pair's size, and scaling by a power
// of two commutes with rounding, so the solver's result is the same bits in any power-of-two
// unit: it runs in metres (the shape matrices of the posed grains are used in place, not
// copied) and only a pair whose smallest semi-axis is outside [2^-200, 2^200] m, where 1/h^3
// could leave the range of doubles, is carried to a unit that brings it into [1, 2).
class PairFrame {
 public:
  PairFrame(const PosedEllipsoid& e1, const PosedEllipsoid& e2, const ContactSolverSettings& settings);
  PairFrame(const PairFrame&) = delete;  // m1, m2 may point into the frame itself
  PairFrame& operator=(const PairFrame&) = delete;

  double scale = 1.0;        // the power of two (1 for every physical grain size)
  Vec3 d;                    // (c1 - c2) * scale
  const Mat3* m1 = nullptr;  // M_i = R_i diag(a_i^2, b_i^2, c_i^2) R_i^T, scaled
  const Mat3* m2 = nullptr;
  const Mat3* rot1 = nullptr;  // R_i (columns: body axes in the world), not scaled
  const Mat3* rot2 = nullptr;
  Vec3 ax1, ax2;         // semi-axes, scaled
  double size = 1.0;     // |d|_1 + a1 + a2: bounds the terms of f and its gradient (round-off scale)
  double certify = 0.0;  // c1^2/a1 + c2^2/a2: smallest radius of curvature of B1 - B2 (D4)
  double tol_g = 0.0;    // Newton's stopping gradient (ContactSolverSettings), scaled
  int max_iterations = 0;

 private:
  Mat3 m1_scaled_, m2_scaled_;  // only for grain sizes outside [2^-200, 2^200] m
};

// A_i v = R_i diag(1/a^2, 1/b^2, 1/c^2) R_i^T v: the normal direction of the surface point
// of body i along v.
Vec3 inverse_shape_times(const Mat3& rot, const Vec3& axes, const Vec3& v) {
  return rot * (rot.transpose() * v).cwiseQuotient(axes.cwiseAbs2());
}

// 2^-floor(log2 c): the power of two that brings c into [1, 2).
double scale_for(double c) { return std::ldexp(1.0, -std::ilogb(c)); }

PairFrame::PairFrame(const PosedEllipsoid& e1, const PosedEllipsoid& e2,
                     const ContactSolverSettings& settings) {
  const double minor = std::min(e1.minor, e2.minor);
  scale = (minor >= kUnscaledLow && minor <= kUnscaledHigh) ? 1.0 : scale_for(minor);
  d = e1.centre - e2.centre;
  rot1 = &e1.rot;
  rot2 = &e2.rot;
  ax1 = e1.semi_axes;
  ax2 = e2.semi_axes;
  m1 = &e1.shape;
  m2 = &e2.shape;
  double major = e1.major + e2.major;
  double min_radius = e1.min_radius + e2.min_radius;
  if (scale != 1.0) {  // exact: equal to the same expressions of the scaled lengths bit for bit
    d *= scale;
    ax1 *= scale;
    ax2 *= scale;
    m1_scaled_ = e1.shape * (scale * scale);
    m2_scaled_ = e2.shape * (scale * scale);
    m1 = &m1_scaled_;
    m2 = &m2_scaled_;
    major *= scale;
    min_radius *= scale;
  }
  size = d.cwiseAbs().sum() + major;
  certify = min_radius;
  tol_g = settings.gradient_tolerance * kEps * size;
  max_iterations = settings.max_iterations;
}

// f(n) and the pieces its derivatives and the contact points reuse (D2): u = M1 n,
// h1 = sqrt(n.u), v = M2 n, h2 = sqrt(n.v), f = n.d + h1 + h2. The gradient of f extended to
// R^3, G = d + u/h1 + v/h2 = p1 - p2 (the two support points), is formed where needed.
struct Eval {
  double f;
  Vec3 u, v;
  double h1, h2;
};

Eval evaluate(const PairFrame& p, const Vec3& n) {
  Eval e;
  e.u = *p.m1 * n;
  e.v = *p.m2 * n;
  e.h1 = std::sqrt(n.dot(e.u));
  e.h2 = std::sqrt(n.dot(e.v));
  e.f = n.dot(p.d) + e.h1 + e.h2;
  return e;
}

// An evaluation in world units carried into a frame: every piece scales by the frame's power
// of two `scale`, exactly. `normal_scale` = 1/l carries an evaluation at l n to one at n:
// u, v, h1, h2 and f scale with it.
Eval scaled(Eval e, double scale, double normal_scale) {
  e.u *= scale * scale * normal_scale;
  e.v *= scale * scale * normal_scale;
  e.h1 *= scale * normal_scale;
  e.h2 *= scale * normal_scale;
  e.f *= scale * normal_scale;
  return e;
}

// Orthonormal tangent basis of a unit vector (Duff et al., JCGT 6(1), 2017): no branch on
// a threshold, so the basis varies smoothly within each hemisphere of n.z.
void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  t1 = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t2 = Vec3(b, sign + n.y() * n.y() * a, -n.y());
}

// Eigenvalues l0 >= l1 of the symmetric [[p, q], [q, r]].
void symmetric_eigenvalues_2x2(double p, double q, double r, double& l0, double& l1) {
  const double mean = 0.5 * (p + r);
  const double half = 0.5 * (p - r);
  const double radius = std::sqrt(half * half + q * q);
  l0 = mean + radius;
  l1 = mean - radius;
}

// The same with the unit eigenvector (c, s) of l0, from the better-conditioned row of
// (matrix - l1): no trigonometry.
void symmetric_eigen_2x2(double p, double q, double r, double& l0, double& l1, double& c, double& s) {
  symmetric_eigenvalues_2x2(p, q, r, l0, l1);
  double x = p - l1, y = q;  // first row of (matrix - l1): parallel to the l0 eigenvector
  if (r - l1 > x) {
    x = q;
    y = r - l1;
  }
  const double len = std::sqrt(x * x + y * y);
  if (len > 0.0) {
    c = x / len;
    s = y / len;
  } else {  // isotropic: every direction is principal
    c = 1.0;
    s = 0.0;
  }
}

struct NewtonResult {
  Vec3 n;
  Eval e;
  int iterations = 0;
  bool converged = false;
};

// Riemannian Newton on the unit sphere (D3). In a tangent basis (t1, t2) of n the gradient is
// g_i = t_i.G and the Hessian H_ij = t_i^T H3 t_j - f delta_ij, with the R^3 Hessian
// H3 = M1/h1 - u u^T/h1^3 + M2/h2 - v v^T/h2^3. Far from a minimum H may be indefinite: it is
// shifted to positive definite (Levenberg), the step is capped at 0.5 rad and backtracked
// until f decreases (Armijo), so every run descends and cannot cycle.
// `at_start`: f at `start`, which must then be a unit vector (the caller's evaluation).
//
// The common case, a warm start one small step from the minimum, is straight-line code with
// two square roots and four divisions: the gradient and the Hessian share the reciprocals
// 1/h1, 1/h2; the convergence and definiteness tests compare squares and a determinant
// instead of taking norms and eigenvalues; and a step below kAngleConverged is retracted to
// the sphere by one Newton step for 1/sqrt (|n + x|^2 = 1 + |x|^2 <= 1 + 1e-12, so its error
// is below 1e-24) instead of a normalisation.
NewtonResult newton_on_sphere(const PairFrame& p, const Vec3& start, const Eval* at_start = nullptr) {
  NewtonResult r;
  r.n = at_start ? start : start.normalized();
  r.e = at_start ? *at_start : evaluate(p, r.n);
  const double tol_g = p.tol_g;
  const double noise_f = 64.0 * kEps * p.size;  // round-off level of f
  const Mat3& m1 = *p.m1;
  const Mat3& m2 = *p.m2;
  for (;;) {
    const double r1 = 1.0 / r.e.h1, r2 = 1.0 / r.e.h2;
    const Vec3 grad = p.d + r.e.u * r1 + r.e.v * r2;
    Vec3 t1, t2;
    tangent_basis(r.n, t1, t2);
    const double g1 = t1.dot(grad), g2 = t2.dot(grad);
    const double g_norm2 = g1 * g1 + g2 * g2;
    if (g_norm2 <= tol_g * tol_g) {
      r.converged = true;
      return r;
    }
    // H3 restricted to the tangent plane: with S = M1/h1 + M2/h2 (symmetric) one pair of
    // products S t1, S t2 instead of four.
    Mat3 s_mat;
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b) s_mat(a, b) = s_mat(b, a) = m1(a, b) * r1 + m2(a, b) * r2;
    const Vec3 st1 = s_mat * t1, st2 = s_mat * t2;
    const double r1_3 = r1 * r1 * r1, r2_3 = r2 * r2 * r2;
    const double u1 = t1.dot(r.e.u), u2 = t2.dot(r.e.u), v1 = t1.dot(r.e.v), v2 = t2.dot(r.e.v);
    double h11 = t1.dot(st1) - u1 * u1 * r1_3 - v1 * v1 * r2_3 - r.e.f;
    double h22 = t2.dot(st2) - u2 * u2 * r1_3 - v2 * v2 * r2_3 - r.e.f;
    const double h12 = t1.dot(st2) - u1 * u2 * r1_3 - v1 * v2 * r2_3;
    // Not shifted when the smaller eigenvalue l1 >= 1e-3 (|l0| + certify). With l0 + l1 = tr H
    // that is l1 >= kappa = 1e-3 (tr H + certify) / 1.001 > 0, i.e. H - kappa 1 positive
    // semi-definite: its diagonal entries and determinant non-negative. No square root.
    const double kappa = 1e-3 * (h11 + h22 + p.certify) / 1.001;
    const double a11 = h11 - kappa, a22 = h22 - kappa;
    const bool shifted = !(kappa > 0.0 && a11 >= 0.0 && a22 >= 0.0 && a11 * a22 - h12 * h12 >= 0.0);
    if (shifted) {  // Levenberg shift to a positive-definite model
      double l0, l1;
      symmetric_eigenvalues_2x2(h11, h12, h22, l0, l1);
      const double floor = 1e-3 * (std::abs(l0) + p.certify);
      h11 += floor - l1;
      h22 += floor - l1;
    }
    const double inv_det = 1.0 / (h11 * h22 - h12 * h12);
    double x1 = -(h22 * g1 - h12 * g2) * inv_det;
    double x2 = -(h11 * g2 - h12 * g1) * inv_det;
    const double step2 = x1 * x1 + x2 * x2;
    // The Newton step of a positive-definite Hessian estimates the angle between n and the
    // minimiser: below kAngleConverged, take it unchecked (it leaves an error ~ step^2) and stop.
    if (!shifted && step2 <= kAngleConverged * kAngleConverged) {
      Vec3 n = r.n + x1 * t1 + x2 * t2;
      n *= 1.5 - 0.5 * n.squaredNorm();
      r.n = n;
      r.e = evaluate(p, r.n);
      ++r.iterations;
      r.converged = true;
      return r;
    }
    if (r.iterations >= p.max_iterations) return r;
    if (step2 > 0.25) {
      const double cap = 0.5 / std::sqrt(step2);
      x1 *= cap;
      x2 *= cap;
    }
    const double slope = g1 * x1 + g2 * x2;  // < 0: a descent direction
    double alpha = 1.0;
    bool accepted = false;
    for (int k = 0; k < 40; ++k) {
      const Vec3 n_try = (r.n + alpha * (x1 * t1 + x2 * t2)).normalized();
      const Eval e_try = evaluate(p, n_try);
      // Armijo decrease; or a full step whose predicted decrease is below the round-off of f,
      // which the test cannot resolve: Newton's local regime, take it.
      if (e_try.f <= r.e.f + 1e-4 * alpha * slope || (k == 0 && -slope <= noise_f)) {
        r.n = n_try;
        r.e = e_try;
        accepted = true;
        break;
      }
      alpha *= 0.5;
    }
    ++r.iterations;
    if (!accepted) {  // no decrease at any step length: at the minimum to round-off, or stuck
      r.converged = g_norm2 <= 1e6 * tol_g * tol_g;
      return r;
    }
  }
}

// Principal curvatures at body-frame point y of an ellipsoid with semi-axes ax (D5).
PrincipalCurvatures curvatures_body(const Mat3& rot, const Vec3& ax, const Vec3& y) {
  const Vec3 a_diag = ax.cwiseProduct(ax).cwiseInverse();
  const Vec3 ay = a_diag.cwiseProduct(y);
  const double grad = ay.norm();
  const Vec3 nu = ay / grad;
  Vec3 t1, t2;
  tangent_basis(nu, t1, t2);
  const double s11 = t1.dot(a_diag.cwiseProduct(t1)) / grad;
  const double s12 = t1.dot(a_diag.cwiseProduct(t2)) / grad;
  const double s22 = t2.dot(a_diag.cwiseProduct(t2)) / grad;
  PrincipalCurvatures k;
  double cs, sn;
  symmetric_eigen_2x2(s11, s12, s22, k.k[0], k.k[1], cs, sn);
  k.direction = rot * (cs * t1 + sn * t2);
  return k;
}

// Candidate normals for a cold start (D4), all turned into the half-space n.(c2 - c1) >= 0
// that holds the global minimum: the centre line u0, the surface normals where it leaves each
// body, their bisector, the six body axes and the cross product of the two major axes.
int cold_candidates(const PairFrame& p, std::array<Vec3, 11>& out) {
  const double dn = p.d.norm();
  const Vec3 u0 = dn > 0.0 ? Vec3(-p.d / dn) : Vec3(p.rot1->col(2));
  int count = 0;
  auto add = [&](const Vec3& v) {
    const double len = v.norm();
    if (!(len > 1e-8)) return;
    out[count++] = (v.dot(u0) < 0.0 ? -v : v) / len;
  };
  add(u0);
  const Vec3 n1 = inverse_shape_times(*p.rot1, p.ax1, u0).normalized();
  const Vec3 n2 = inverse_shape_times(*p.rot2, p.ax2, u0).normalized();
  add(n1);
  add(n2);
  add(n1 + n2);
  for (int k = 0; k < 3; ++k) add(p.rot1->col(k));
  for (int k = 0; k < 3; ++k) add(p.rot2->col(k));
  add(p.rot1->col(0).cross(p.rot2->col(0)));
  return count;
}

// Unit vectors spread over the hemisphere around `pole` (Fibonacci lattice), for the fallback.
Vec3 hemisphere_point(const Vec3& pole, int i, int count) {
  Vec3 t1, t2;
  tangent_basis(pole, t1, t2);
  const double z = 1.0 - (i + 0.5) / count;  // cos of the polar angle in (0, 1)
  const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.39996322972865332 * i;  // golden angle
  return z * pole + rho * (std::cos(phi) * t1 + std::sin(phi) * t2);
}

// Multi-start fallback: Newton from every candidate and the best few of a hemisphere lattice;
// the lowest converged stationary point wins.
NewtonResult fallback(const PairFrame& p, const std::array<Vec3, 11>& cands, int n_cands, int& iterations) {
  NewtonResult best;
  best.e.f = std::numeric_limits<double>::infinity();
  auto consider = [&](const Vec3& start) {
    NewtonResult r = newton_on_sphere(p, start);
    iterations += r.iterations;
    const bool better =
        (r.converged && !best.converged) || (r.converged == best.converged && r.e.f < best.e.f);
    if (better) best = r;
  };
  for (int i = 0; i < n_cands; ++i) consider(cands[i]);
  constexpr int kLattice = 96, kKeep = 6;
  std::array<std::pair<double, int>, kLattice> lattice;
  for (int i = 0; i < kLattice; ++i) lattice[i] = {evaluate(p, hemisphere_point(cands[0], i, kLattice)).f, i};
  std::partial_sort(lattice.begin(), lattice.begin() + kKeep, lattice.end());
  for (int k = 0; k < kKeep; ++k) consider(hemisphere_point(cands[0], lattice[k].second, kLattice));
  return best;
}

// Writes the result into `g`, a default ContactGeometry (the fields not set keep their
// defaults), in place: the force loop's result is not copied.
void assemble(const PairFrame& p, const Vec3& centre1, const Vec3& centre2, const NewtonResult& r,
              bool curvatures, ContactGeometry& g) {
  const double inv = 1.0 / p.scale;  // exact: a power of two
  g.depth = r.e.f * inv;
  g.touching = r.e.f > 0.0;
  g.normal = r.n;
  const Vec3 arm1 = r.e.u * (1.0 / r.e.h1);   // p1 - c1, scaled (support point of body 1 along n)
  const Vec3 arm2 = r.e.v * (-1.0 / r.e.h2);  // p2 - c2, scaled (support point of body 2 along -n)
  // The levers from both centres to the mid-point, from c1 - c2 (exact for near centres), not
  // from world positions.
  g.lever1 = (arm1 - 0.5 * r.e.f * r.n) * inv;
  g.lever2 = g.lever1 + p.d * inv;
  g.point1 = centre1 + arm1 * inv;
  g.point2 = centre2 + arm2 * inv;
  g.point = centre1 + g.lever1;
  if (g.touching && curvatures) {  // curvatures feed the contact law only: skipped for gaps
    const PrincipalCurvatures k1 = curvatures_body(*p.rot1, p.ax1, p.rot1->transpose() * arm1);
    const PrincipalCurvatures k2 = curvatures_body(*p.rot2, p.ax2, p.rot2->transpose() * arm2);
    for (int i = 0; i < 2; ++i) {
      g.curvature1[i] = k1.k[i] * p.scale;
      g.curvature2[i] = k2.k[i] * p.scale;
    }
    g.direction1 = k1.direction;
    g.direction2 = k2.direction;
  }
  g.iterations = r.iterations;
  g.converged = r.converged;
  g.certified = r.converged && r.e.f < p.certify * (1.0 - 1e-9);
}

}  // namespace

ContactGeometry sphere_sphere_contact(const Vec3& c1, double r1, const Vec3& c2, double r2) {
  ContactGeometry g;
  const Vec3 d = c2 - c1;
  const double dist = d.norm();
  g.normal = dist > 0.0 ? Vec3(d / dist) : Vec3(Vec3::UnitZ());
  g.depth = r1 + r2 - dist;
  g.touching = g.depth > 0.0;
  g.point1 = c1 + r1 * g.normal;
  g.point2 = c2 - r2 * g.normal;
  g.lever1 = (r1 - 0.5 * g.depth) * g.normal;
  g.lever2 = -(r2 - 0.5 * g.depth) * g.normal;
  g.point = c1 + g.lever1;
  g.curvature1[0] = g.curvature1[1] = 1.0 / r1;
  g.curvature2[0] = g.curvature2[1] = 1.0 / r2;
  Vec3 t2;
  tangent_basis(g.normal, g.direction1, t2);
  g.direction2 = g.direction1;
  return g;
}

ContactGeometry ellipsoid_contact(const Ellipsoid& e1, const Ellipsoid& e2, ContactSolverStats& stats,
                                  const std::optional<Vec3>& initial_normal,
                                  const ContactSolverSettings& settings) {
  if (e1.is_sphere() && e2.is_sphere()) {
    ++stats.calls;
    return sphere_sphere_contact(e1.centre, e1.semi_axes.x(), e2.centre, e2.semi_axes.x());
  }
  return support_function_contact(e1, e2, stats, initial_normal, settings);
}

namespace {

// The solver on a pair frame (D3, D4): warm start, cold start from the best candidate, and the
// multi-start fallback when the result is not certified.
// `at_initial`: f at the initial normal when the caller has it (it must be the normalised one).
void solve_frame(const PairFrame& p, const Vec3& centre1, const Vec3& centre2, ContactSolverStats& stats,
                 const std::optional<Vec3>& initial_normal, bool curvatures, ContactGeometry& g,
                 const Eval* at_initial = nullptr) {
  int iterations = 0;
  if (initial_normal && initial_normal->squaredNorm() > 0.5) {
    ++stats.warm_starts;
    const NewtonResult r = newton_on_sphere(p, *initial_normal, at_initial);
    iterations += r.iterations;
    if (r.converged && r.e.f < p.certify * (1.0 - 1e-9)) {
      stats.newton_iterations += iterations;
      assemble(p, centre1, centre2, r, curvatures, g);
      return;
    }
    ++stats.warm_rejected;
  }
  std::array<Vec3, 11> cands;
  const int n_cands = cold_candidates(p, cands);
  int best = 0;
  double best_f = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_cands; ++i) {
    const double f = evaluate(p, cands[i]).f;
    if (f < best_f) {
      best_f = f;
      best = i;
    }
  }
  NewtonResult r = newton_on_sphere(p, cands[best]);
  iterations += r.iterations;
  // Certified (D4): a stationary point below the smallest radius of curvature of B1 - B2 is
  // the global minimum. Otherwise search more widely before answering.
  if (!(r.converged && r.e.f < p.certify * (1.0 - 1e-9))) {
    ++stats.fallbacks;
    const NewtonResult wide = fallback(p, cands, n_cands, iterations);
    if ((wide.converged && !r.converged) || (wide.converged == r.converged && wide.e.f < r.e.f)) r = wide;
  }
  stats.newton_iterations += iterations;
  assemble(p, centre1, centre2, r, curvatures, g);
  g.iterations = iterations;
  if (!g.converged)
    ++stats.failures;
  else if (!g.certified)
    ++stats.uncertified;
}

// proven_separated() on a frame; `witness` receives the direction that proved it.
bool separated_frame(const PairFrame& p, double margin, Vec3* witness = nullptr) {
  const double dn = p.d.norm();
  if (!(dn > 0.0)) return false;
  const Vec3 u0 = -p.d / dn;
  const double bound = -margin * p.scale;
  auto proves = [&](const Vec3& n) {
    if (!(evaluate(p, n).f < bound)) return false;
    if (witness) *witness = n;
    return true;
  };
  if (proves(u0)) return true;
  if (proves(inverse_shape_times(*p.rot1, p.ax1, u0).normalized())) return true;
  return proves(inverse_shape_times(*p.rot2, p.ax2, u0).normalized());
}

}  // namespace

ContactGeometry support_function_contact(const Ellipsoid& e1, const Ellipsoid& e2, ContactSolverStats& stats,
                                         const std::optional<Vec3>& initial_normal,
                                         const ContactSolverSettings& settings) {
  ++stats.calls;
  const PosedEllipsoid p1 = PosedEllipsoid::from(e1), p2 = PosedEllipsoid::from(e2);
  ContactGeometry g;
  const PairFrame p(p1, p2, settings);
  solve_frame(p, e1.centre, e2.centre, stats, initial_normal, true, g);
  return g;
}

Mat3 PosedEllipsoid::shape_of(const Mat3& rot, const Vec3& semi_axes) {
  // Symmetric: its six distinct entries, from the columns of R weighted by the squared axes.
  const double a2 = semi_axes[0] * semi_axes[0], b2 = semi_axes[1] * semi_axes[1];
  const double c2 = semi_axes[2] * semi_axes[2];
  const double r00 = rot(0, 0), r10 = rot(1, 0), r20 = rot(2, 0);
  const double r01 = rot(0, 1), r11 = rot(1, 1), r21 = rot(2, 1);
  const double r02 = rot(0, 2), r12 = rot(1, 2), r22 = rot(2, 2);
  const double w00 = a2 * r00, w10 = a2 * r10, w20 = a2 * r20;
  const double w01 = b2 * r01, w11 = b2 * r11, w21 = b2 * r21;
  const double w02 = c2 * r02, w12 = c2 * r12, w22 = c2 * r22;
  Mat3 m;
  m(0, 0) = w00 * r00 + w01 * r01 + w02 * r02;
  m(1, 1) = w10 * r10 + w11 * r11 + w12 * r12;
  m(2, 2) = w20 * r20 + w21 * r21 + w22 * r22;
  m(0, 1) = m(1, 0) = w00 * r10 + w01 * r11 + w02 * r12;
  m(0, 2) = m(2, 0) = w00 * r20 + w01 * r21 + w02 * r22;
  m(1, 2) = m(2, 1) = w10 * r20 + w11 * r21 + w12 * r22;
  return m;
}

PosedEllipsoid PosedEllipsoid::from(const Ellipsoid& e) {
  PosedEllipsoid q;
  q.centre = e.centre;
  q.rot = e.orientation.toRotationMatrix();
  q.semi_axes = e.semi_axes;
  q.shape = shape_of(q.rot, e.semi_axes);
  q.major = e.semi_axes.maxCoeff();
  q.minor = e.semi_axes.minCoeff();
  q.min_radius = q.minor * q.minor / q.major;
  return q;
}

namespace {

constexpr int kFastIterations = 4;  // Newton steps of the force loop's straight-line path

}  // namespace

// The straight-line path works in metres: semi-axes in [2^-200, 2^200] m (PairFrame).
bool warm_path_applies(const PosedEllipsoid& e1, const PosedEllipsoid& e2) {
  return std::min(e1.minor, e2.minor) >= kUnscaledLow && std::max(e1.major, e2.major) <= kUnscaledHigh;
}

// posed_contact() after the proof's evaluation q at the pair's last normal.
bool warm_contact_after_proof(const PosedEllipsoid& e1, const PosedEllipsoid& e2,
                              const warm::PairLanes<double>& p, warm::PointLanes<double>& q, bool radius,
                              const ContactSolverSettings& settings, ContactSolverStats& stats,
                              PairContact& out);

namespace {

// The force loop's usual case (docs/ellipsoid-contact.md, "In the force loop"): a pair near its
// last normal, Newton from there in metres, as newton_on_sphere() but written out for the
// symmetric shape matrices, with no frame, no copies and no line search. Gives up (false, with
// nothing counted, `out` untouched; `q` is overwritten, so the caller keeps its own copy of
// the start) whenever the general solver would do something else: an
// indefinite model, a step above 0.1 rad or one that fails the Armijo test, more than
// min(kFastIterations, settings.max_iterations) steps, or a result the certificate (D4) does not cover; the
// caller then runs the general solver from the same start. `q` holds f at the unit start; the pieces are
// those of warm_newton.h, which the force loop also runs two pairs at a time.
bool warm_newton(const warm::PairLanes<double>& p, warm::PointLanes<double>& q,
                 const ContactSolverSettings& settings, ContactSolverStats& stats, PairContact& out) {
  const double tol_g = settings.gradient_tolerance * kEps * p.size, noise_f = 64.0 * kEps * p.size;
  const int cap = std::min(kFastIterations, settings.max_iterations);
  int iterations = 0;
  for (;;) {
    warm::GradientLanes<double> g;
    warm::gradient(p, q, g);
    if (g.norm2 <= tol_g * tol_g) break;  // at the minimum to round-off
    if (iterations == cap) return false;
    bool definite;
    double x1, x2;
    warm::newton_step(p, q, g, definite, x1, x2);
    if (!definite) return false;
    const double step2 = x1 * x1 + x2 * x2;
    if (!(step2 <= 1e-2)) return false;  // above 0.1 rad: the general solver's capped line search
    const double f_before = q.f;
    ++iterations;
    if (step2 <= kAngleConverged * kAngleConverged) {  // taken unchecked, as newton_on_sphere()
      warm::small_step(g, x1, x2, q);
      warm::evaluate(p, q);
      break;
    }
    const double slope = g.g1 * x1 + g.g2 * x2;
    double m[3];
    for (int k = 0; k < 3; ++k) m[k] = q.n[k] + x1 * g.t1[k] + x2 * g.t2[k];
    const double to_unit = 1.0 / std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (int k = 0; k < 3; ++k) q.n[k] = m[k] * to_unit;
    warm::evaluate(p, q);
    if (!(q.f <= f_before + 1e-4 * slope || -slope <= noise_f)) return false;
  }
  if (!(q.f < p.certify * (1.0 - 1e-9))) return false;  // D4 does not cover it: the general solver
  double l1[3], l2[3];
  warm::levers(p, q, l1, l2);
  out.depth = q.f;
  out.normal = Vec3(q.n[0], q.n[1], q.n[2]);
  out.lever1 = Vec3(l1[0], l1[1], l1[2]);
  out.lever2 = Vec3(l2[0], l2[1], l2[2]);
  out.gaussian_radius = 0.0;
  ++stats.warm_starts;
  stats.newton_iterations += iterations;
  return true;
}

// What the force loop keeps of a full result.
bool to_pair_contact(const ContactGeometry& g, bool radius, PairContact& out) {
  out.depth = g.depth;
  out.normal = g.normal;
  out.lever1 = g.lever1;
  out.lever2 = g.lever2;
  out.gaussian_radius = g.touching && radius ? gaussian_curvature_radius(g) : 0.0;
  return g.touching;
}

}  // namespace

bool posed_contact(const PosedEllipsoid& e1, const PosedEllipsoid& e2, const Vec3* last_normal, bool radius,
                   const ContactSolverSettings& settings, ContactSolverStats& stats, PairContact& out) {
  if (e1.is_sphere() && e2.is_sphere()) {
    ++stats.calls;
    return to_pair_contact(sphere_sphere_contact(e1.centre, e1.semi_axes.x(), e2.centre, e2.semi_axes.x()),
                           radius, out);
  }
  const bool warm = last_normal && last_normal->squaredNorm() > 0.5;
  if (!warm) {
    const PairFrame p(e1, e2, settings);
    Vec3 witness;
    if (separated_frame(p, 0.0, &witness)) {
      ++stats.proven_apart;
      out.normal = witness;
      out.depth = evaluate(p, witness).f / p.scale;
      return false;
    }
    ++stats.calls;
    ContactGeometry g;
    solve_frame(p, e1.centre, e2.centre, stats, std::nullopt, radius, g);
    return to_pair_contact(g, radius, out);
  }
  // f is homogeneous of degree one, f(l n) = l f(n) for l > 0: the proof needs no unit n.
  // Half the warm pairs of a bed end here, before anything else is computed.
  const Vec3& m = *last_normal;
  const Vec3 d = e1.centre - e2.centre;
  warm::PairLanes<double> p;
  warm::load_pair(e1, e2, d, p);
  warm::PointLanes<double> q;
  for (int k = 0; k < 3; ++k) q.n[k] = m[k];
  warm::evaluate(p, q);
  return warm_contact_after_proof(e1, e2, p, q, radius, settings, stats, out);
}

bool warm_contact_after_proof(const PosedEllipsoid& e1, const PosedEllipsoid& e2,
                              const warm::PairLanes<double>& p, warm::PointLanes<double>& q, bool radius,
                              const ContactSolverSettings& settings, ContactSolverStats& stats,
                              PairContact& out) {
  const Vec3 m(q.n[0], q.n[1], q.n[2]);
  if (q.f < 0.0) {
    ++stats.proven_apart;
    out.normal = m;
    out.depth = q.f;
    return false;
  }
  ++stats.calls;
  // A stored normal is unit to round-off: the proof's evaluation is Newton's first. The
  // straight-line path needs no curvatures (first touch takes the general one) and grain sizes
  // in [2^-200, 2^200] m, where the pair frame is in metres.
  const Eval at_m{q.f, Vec3(q.u[0], q.u[1], q.u[2]), Vec3(q.v[0], q.v[1], q.v[2]), q.h1, q.h2};
  const double mm = m.squaredNorm();
  const bool unit = std::abs(mm - 1.0) <= 64.0 * kEps;
  if (unit && !radius && warm_path_applies(e1, e2) && warm_newton(p, q, settings, stats, out))
    return out.depth > 0.0;
  const PairFrame frame(e1, e2, settings);
  const double inv_len = unit ? 1.0 : 1.0 / std::sqrt(mm);
  const Eval at_n = scaled(at_m, frame.scale, inv_len);
  ContactGeometry g;
  solve_frame(frame, e1.centre, e2.centre, stats, m * inv_len, radius, g, &at_n);
  return to_pair_contact(g, radius, out);
}

void posed_contacts_two(WarmPairSolve& pair_a, WarmPairSolve& pair_b, const ContactSolverSettings& settings,
                        ContactSolverStats& stats) {
  const PosedEllipsoid &a1 = *pair_a.first, &a2 = *pair_a.second, &b1 = *pair_b.first, &b2 = *pair_b.second;
  const Vec3 &last_a = pair_a.last_normal, &last_b = pair_b.last_normal;
  PairContact &out_a = pair_a.out, &out_b = pair_b.out;
  bool &touching_a = pair_a.touching, &touching_b = pair_b.touching;
  using warm::Mask;
  using warm::Pair;
  // The caller's precondition (shaped_pair_geometries() sorts the pairs so): warm pairs, each
  // with an ellipsoid. Checked in debug builds (the sanitizer build runs every unit test) rather
  // than here on every call: the check cost 2.4 % of the ellipsoid bed's instructions.
  assert(!(a1.is_sphere() && a2.is_sphere()) && !(b1.is_sphere() && b2.is_sphere()));
  assert(std::abs(last_a.squaredNorm() - 1.0) < 1e-6 && std::abs(last_b.squaredNorm() - 1.0) < 1e-6);
  const Vec3 da = a1.centre - a2.centre, db = b1.centre - b2.centre;
  warm::PairLanes<double> pa, pb;
  warm::load_pair(a1, a2, da, pa);
  warm::load_pair(b1, b2, db, pb);
  warm::PairLanes<Pair> p;
  for (int k = 0; k < 6; ++k) {
    p.a[k] = Pair{pa.a[k], pb.a[k]};
    p.b[k] = Pair{pa.b[k], pb.b[k]};
  }
  for (int k = 0; k < 3; ++k) p.d[k] = Pair{pa.d[k], pb.d[k]};
  p.size = Pair{pa.size, pb.size};
  p.certify = Pair{pa.certify, pb.certify};
  warm::PointLanes<Pair> q;
  for (int k = 0; k < 3; ++k) q.n[k] = Pair{last_a[k], last_b[k]};
  warm::evaluate(p, q);
  // Each pair alone from its proof's evaluation (the same bits as the lanes'): when a pair is
  // proven apart, or either leaves the straight-line path.
  auto alone = [&] {
    warm::PointLanes<double> qa, qb;
    for (int lane = 0; lane < 2; ++lane) {
      warm::PointLanes<double>& one = lane == 0 ? qa : qb;
      for (int k = 0; k < 3; ++k) {
        one.n[k] = q.n[k][lane];
        one.u[k] = q.u[k][lane];
        one.v[k] = q.v[k][lane];
      }
      one.h1 = q.h1[lane];
      one.h2 = q.h2[lane];
      one.f = q.f[lane];
    }
    touching_a = warm_contact_after_proof(a1, a2, pa, qa, false, settings, stats, out_a);
    touching_b = warm_contact_after_proof(b1, b2, pb, qb, false, settings, stats, out_b);
  };
  const bool unit = std::abs(last_a.squaredNorm() - 1.0) <= 64.0 * kEps &&
                    std::abs(last_b.squaredNorm() - 1.0) <= 64.0 * kEps;
  if (!(q.f[0] >= 0.0 && q.f[1] >= 0.0) || !unit || !warm_path_applies(a1, a2) ||
      !warm_path_applies(b1, b2)) {
    alone();
    return;
  }
  // warm_newton()'s loop in both lanes. A lane that has stopped keeps its point (the other's
  // further steps are blended out); any lane that would leave the straight-line path sends both
  // to the one-pair code.
  auto blend = [](Mask m, Pair a, Pair b) {
    return std::bit_cast<Pair>((std::bit_cast<Mask>(a) & m) | (std::bit_cast<Mask>(b) & ~m));
  };
  const warm::PointLanes<Pair> at_m = q;
  auto give_up = [&] {
    q = at_m;
    alone();
  };
  const Pair tol_g = settings.gradient_tolerance * kEps * p.size, noise_f = 64.0 * kEps * p.size;
  const int cap = std::min(kFastIterations, settings.max_iterations);
  Mask done = {0, 0};
  int iterations[2] = {0, 0};
  for (;;) {
    warm::GradientLanes<Pair> g;
    warm::gradient(p, q, g);
    done |= g.norm2 <= tol_g * tol_g;  // at the minimum to round-off (or stopped before)
    if (done[0] && done[1]) break;
    const Mask active = ~done;
    Mask definite;
    Pair x1, x2;
    warm::newton_step(p, q, g, definite, x1, x2);
    const Pair step2 = x1 * x1 + x2 * x2;
    const Mask stays = definite & (step2 <= 1e-2);
    for (int lane = 0; lane < 2; ++lane)
      if (active[lane] && (iterations[lane] == cap || !stays[lane])) {
        give_up();
        return;
      }
    const Mask last = step2 <= kAngleConverged * kAngleConverged;
    // The next point: a step below 1e-6 rad retracted by one Newton step for 1/sqrt, a larger one
    // normalised (warm_newton()'s two branches, chosen per lane).
    warm::PointLanes<Pair> next = q;
    Pair m[3];
    for (int k = 0; k < 3; ++k) m[k] = q.n[k] + x1 * g.t1[k] + x2 * g.t2[k];
    const Pair norm2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
    const Pair small = 1.5 - 0.5 * norm2;
    const Pair to_unit = last[0] && last[1] ? small : blend(last, small, 1.0 / warm::sqrt_of(norm2));
    for (int k = 0; k < 3; ++k) next.n[k] = m[k] * to_unit;
    warm::evaluate(p, next);
    if (!(last[0] && last[1])) {  // the Armijo test of the larger steps
      const Pair slope = g.g1 * x1 + g.g2 * x2;
      const Mask decreases = (next.f <= q.f + 1e-4 * slope) | (-slope <= noise_f);
      for (int lane = 0; lane < 2; ++lane)
        if (active[lane] && !last[lane] && !decreases[lane]) {
          give_up();
          return;
        }
    }
    if (active[0] && active[1]) {
      q = next;
    } else {
      for (int k = 0; k < 3; ++k) {
        q.n[k] = blend(active, next.n[k], q.n[k]);
        q.u[k] = blend(active, next.u[k], q.u[k]);
        q.v[k] = blend(active, next.v[k], q.v[k]);
      }
      q.h1 = blend(active, next.h1, q.h1);
      q.h2 = blend(active, next.h2, q.h2);
      q.f = blend(active, next.f, q.f);
    }
    for (int lane = 0; lane < 2; ++lane) iterations[lane] += active[lane] ? 1 : 0;
    done |= active & last;  // taken unchecked, as newton_on_sphere()
    if (done[0] && done[1]) break;
  }
  const Mask certified = q.f < p.certify * (1.0 - 1e-9);
  if (!(certified[0] && certified[1])) {
    give_up();
    return;
  }
  Pair l1[3], l2[3];
  warm::levers(p, q, l1, l2);
  for (int lane = 0; lane < 2; ++lane) {
    PairContact& out = lane == 0 ? out_a : out_b;
    out.depth = q.f[lane];
    out.normal = Vec3(q.n[0][lane], q.n[1][lane], q.n[2][lane]);
    out.lever1 = Vec3(l1[0][lane], l1[1][lane], l1[2][lane]);
    out.lever2 = Vec3(l2[0][lane], l2[1][lane], l2[2][lane]);
    out.gaussian_radius = 0.0;
  }
  touching_a = q.f[0] > 0.0;
  touching_b = q.f[1] > 0.0;
  stats.calls += 2;
  stats.warm_starts += 2;
  stats.newton_iterations += iterations[0] + iterations[1];
}

ContactGeometry ellipsoid_sphere_contact(const Ellipsoid& e, const Vec3& centre, double radius,
                                         ContactSolverStats& stats, const std::optional<Vec3>& initial_normal,
                                         const ContactSolverSettings& settings) {
  return ellipsoid_contact(e, Ellipsoid::sphere(centre, radius), stats, initial_normal, settings);
}

ContactGeometry ellipsoid_plane_contact(const Ellipsoid& e, const Plane& plane) {
  return posed_plane_contact(PosedEllipsoid::from(e), plane, true);
}

ContactGeometry posed_plane_contact(const PosedEllipsoid& e, const Plane& plane, bool curvatures) {
  ContactGeometry g;
  const Mat3& rot = e.rot;
  const Vec3 m = plane.normal;
  const Vec3 mm = e.shape * m;
  const double h = std::sqrt(m.dot(mm));
  const Vec3 arm = -mm / h;  // lowest point of the ellipsoid along -m, relative to its centre
  g.depth = h - m.dot(e.centre - plane.point);
  g.touching = g.depth > 0.0;
  g.normal = -m;
  g.point1 = e.centre + arm;
  g.point2 = e.centre + (arm + g.depth * m);
  g.lever1 = arm + 0.5 * g.depth * m;
  g.point = e.centre + g.lever1;
  if (!curvatures) return g;
  const PrincipalCurvatures k = curvatures_body(rot, e.semi_axes, rot.transpose() * arm);
  g.curvature1[0] = k.k[0];
  g.curvature1[1] = k.k[1];
  g.direction1 = k.direction;
  g.direction2 = k.direction;
  return g;
}

double support_gap_function(const Ellipsoid& e1, const Ellipsoid& e2, const Vec3& n) {
  const PosedEllipsoid p1 = PosedEllipsoid::from(e1), p2 = PosedEllipsoid::from(e2);
  const PairFrame p(p1, p2, {});
  return evaluate(p, n).f / p.scale;
}

bool proven_separated(const Ellipsoid& e1, const Ellipsoid& e2, double margin) {
  const PosedEllipsoid p1 = PosedEllipsoid::from(e1), p2 = PosedEllipsoid::from(e2);
  const PairFrame p(p1, p2, {});
  return separated_frame(p, margin);
}

PrincipalCurvatures principal_curvatures(const Ellipsoid& e, const Vec3& surface_point) {
  const Mat3 rot = e.orientation.toRotationMatrix();
  return curvatures_body(rot, e.semi_axes, rot.transpose() * (surface_point - e.centre));
}

RelativeCurvature relative_curvature(const ContactGeometry& g) {
  // Curvature tensors of both surfaces in the common tangent plane (t1, t2) of the normal;
  // the relative curvature is half their sum and A, B its eigenvalues (Johnson 1985, eq. 4.2-4.4).
  const Vec3 t1 = (g.direction1 - g.direction1.dot(g.normal) * g.normal).normalized();
  const Vec3 t2 = g.normal.cross(t1);
  const double c = g.direction2.dot(t1), s = g.direction2.dot(t2);
  const double len = std::sqrt(c * c + s * s);
  const double c2 = len > 0.0 ? c / len : 1.0, s2 = len > 0.0 ? s / len : 0.0;
  const double p = 0.5 * (g.curvature1[0] + g.curvature2[0] * c2 * c2 + g.curvature2[1] * s2 * s2);
  const double r = 0.5 * (g.curvature1[1] + g.curvature2[0] * s2 * s2 + g.curvature2[1] * c2 * c2);
  const double q = 0.5 * (g.curvature2[0] - g.curvature2[1]) * c2 * s2;
  RelativeCurvature rc;
  double l0, l1, cs, sn;
  symmetric_eigen_2x2(p, q, r, l0, l1, cs, sn);
  rc.a = l1;
  rc.b = l0;
  return rc;
}

double mean_curvature_radius(const ContactGeometry& g) {
  return 2.0 / (g.curvature1[0] + g.curvature1[1] + g.curvature2[0] + g.curvature2[1]);
}

double gaussian_curvature_radius(const ContactGeometry& g) {
  const RelativeCurvature rc = relative_curvature(g);
  return 0.5 / std::sqrt(rc.a * rc.b);
}

}  // namespace upgrain::dem
