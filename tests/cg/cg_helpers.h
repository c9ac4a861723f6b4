#pragma once
// Independent numbers for the coarse-graining tests: Gauss-Legendre quadrature, the line
// integral by quadrature, small granular states built by hand.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "upscale/cg/coarse_grained_fields.h"
#include "upscale/cg/grain_state.h"

namespace upgrain::upscale::cg::test {

// Nodes and weights of n-point Gauss-Legendre on [-1, 1] (Newton on P_n).
inline void legendre_rule(int n, std::vector<double>& x, std::vector<double>& w) {
  // P_n(z) and P_n'(z) by the three-term recurrence.
  auto legendre = [n](double z, double& p, double& dp) {
    double p0 = 1.0, p1 = z;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    p = p1;
    dp = n * (z * p1 - p0) / (z * z - 1.0);
  };
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), p = 0.0, dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      legendre(z, p, dp);
      const double dz = p / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    legendre(z, p, dp);
    x[i] = z;
    w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

// Composite Gauss-Legendre, 20 points on each of `panels` equal panels of [a, b].
template <class F>
double gauss_legendre(double a, double b, F&& f, int panels) {
  static std::vector<double> x, w;
  if (x.empty()) legendre_rule(20, x, w);
  double sum = 0.0;
  const double h = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    const double m = a + (p + 0.5) * h;
    for (std::size_t i = 0; i < x.size(); ++i) sum += w[i] * 0.5 * h * f(m + 0.5 * h * x[i]);
  }
  return sum;
}

// int_0^1 phi(|d - s l|) ds by quadrature, the interval split where |d - s l| = cut-off, so
// that each piece is smooth.
template <class K>
double line_integral_by_quadrature(const K& k, const Vec3& d, const Vec3& l) {
  std::vector<double> cuts{0.0, 1.0};
  const double a = l.squaredNorm(), b = -2.0 * d.dot(l), c = d.squaredNorm() - k.cutoff() * k.cutoff();
  const double disc = b * b - 4 * a * c;
  if (a > 0 && disc > 0)
    for (double s : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)})
      if (s > 0 && s < 1) cuts.push_back(s);
  // The foot of the point (where |d - s l| is least: Lucy's r^3 term is not smooth there).
  if (a > 0) {
    const double s = d.dot(l) / a;
    if (s > 0 && s < 1) cuts.push_back(s);
  }
  std::sort(cuts.begin(), cuts.end());
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    sum += gauss_legendre(
        cuts[i], cuts[i + 1], [&](double s) { return k.value((d - s * l).squaredNorm()); }, 40);
  return sum;
}

// Adds a grain at rest with the given mass and volume.
inline void add_grain(GrainState& s, GlobalId id, const Vec3& x, double mass, double volume,
                      const Vec3& v = Vec3::Zero(), const Vec3& a = Vec3::Zero()) {
  s.id.push_back(id);
  s.x.push_back(x);
  s.v.push_back(v);
  s.acceleration.push_back(a);
  s.mass.push_back(mass);
  s.volume.push_back(volume);
}

// A contact between grains a and b (indices) at `point`, force f on a: its two branches.
inline void add_contact(GrainState& s, std::size_t a, std::size_t b, const Vec3& point, const Vec3& f) {
  for (auto [from, force] : {std::pair{s.x[a], f}, std::pair{s.x[b], Vec3(-f)}}) {
    s.branch_from.push_back(from);
    s.branch_to.push_back(point);
    s.branch_force.push_back(force);
    s.ends_at_grain.push_back(0);
    s.longest_branch = std::max(s.longest_branch, (point - from).norm());
  }
}

// A wall contact of grain a at `point`, force f of the wall on a.
inline void add_wall_contact(GrainState& s, std::size_t a, const Vec3& point, const Vec3& f) {
  s.branch_from.push_back(s.x[a]);
  s.branch_to.push_back(point);
  s.branch_force.push_back(f);
  s.ends_at_grain.push_back(0);
  s.longest_branch = std::max(s.longest_branch, (point - s.x[a]).norm());
  s.wall_point.push_back(point);
  s.wall_force.push_back(f);
}

// Grains at random in a box, contacts between close pairs with random forces (not in
// balance), wall contacts at the floor; random velocities and accelerations.
inline GrainState random_state(unsigned seed, int grains = 300) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), f(-1.0, 1.0);
  GrainState s;
  s.gravity = Vec3(0.3, -0.2, -9.81);
  for (int i = 0; i < grains; ++i)
    add_grain(s, i, Vec3(u(rng), u(rng), 0.6 * u(rng)) * 0.02, 1e-4 * (1 + u(rng)), 4e-8 * (1 + u(rng)),
              Vec3(f(rng), f(rng), f(rng)) * 0.1, Vec3(f(rng), f(rng), f(rng)) * 5);
  for (std::size_t a = 0; a < s.grains(); ++a) {
    for (std::size_t b = a + 1; b < s.grains(); ++b)
      if ((s.x[a] - s.x[b]).norm() < 3e-3)
        add_contact(s, a, b, 0.5 * (s.x[a] + s.x[b]) + Vec3(f(rng), f(rng), f(rng)) * 2e-4,
                    Vec3(f(rng), f(rng), f(rng)) * 1e-3);
    if (s.x[a].z() < 1.5e-3)
      add_wall_contact(s, a, Vec3(s.x[a].x(), s.x[a].y(), 0.0), Vec3(f(rng), f(rng), 2) * 1e-3);
  }
  return s;
}

inline std::vector<Vec3> random_points(unsigned seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) p.emplace_back(Vec3(u(rng), u(rng), 0.6 * u(rng)) * 0.02);
  return p;
}

// Whether x lies within `band` of the cut-off sphere around an end of a branch (where the
// cut Gaussian's stress has a kink, so central differences across it lose their order).
template <class K>
bool near_a_kink(const GrainState& s, const K& kernel, const Vec3& x, double band) {
  if (!std::is_same_v<K, GaussianKernel>) return false;
  for (std::size_t k = 0; k < s.branches(); ++k)
    for (const Vec3& end : {s.branch_from[k], s.branch_to[k]})
      if (std::abs((x - end).norm() - kernel.cutoff()) < band) return true;
  return false;
}

// div of a stress field (member `stress` of the fields) at x by central differences of step h.
template <class K>
Vec3 divergence_by_differences(const GrainState& s, const K& kernel, const Vec3& x, double h,
                               std::vector<Mat3> CoarseGrainedFields::*stress) {
  Vec3 div = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    Vec3 e = Vec3::Zero();
    e[j] = h;
    const CoarseGrainedFields g = coarse_grain(s, std::vector<Vec3>{x + e, x - e}, kernel);
    div += ((g.*stress)[0] - (g.*stress)[1]).col(j) / (2 * h);
  }
  return div;
}

}  // namespace upgrain::upscale::cg::test
