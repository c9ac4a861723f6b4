#include "dem/analysis/oedometer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "dem/contact/hertz_mindlin.h"
#include "dem/core/error.h"

namespace upgrain::dem {

double poisson_from_k0(double k0) { return k0 / (1.0 + k0); }

double youngs_from_constrained(double constrained_modulus, double poisson) {
  return constrained_modulus * (1.0 + poisson) * (1.0 - 2.0 * poisson) / (1.0 - poisson);
}

namespace {
double k0_of(const OedometerState& s) { return s.horizontal_stress / s.vertical_stress; }
}  // namespace

std::vector<OedometerStep> oedometer_steps(const std::vector<OedometerState>& path) {
  std::vector<OedometerStep> steps;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const OedometerState &a = path[k - 1], &b = path[k];
    const double de = b.vertical_strain - a.vertical_strain;
    if (!(de > 0.0))
      throw Error("oedometric path: the strain does not grow from state " + std::to_string(k - 1) + " to " +
                  std::to_string(k) + " (" + std::to_string(a.vertical_strain) + " -> " +
                  std::to_string(b.vertical_strain) + ")");
    OedometerStep s;
    s.stress = 0.5 * (a.vertical_stress + b.vertical_stress);
    s.modulus = (b.vertical_stress - a.vertical_stress) / de;
    s.k0 = k0_of(b);
    s.poisson = poisson_from_k0(s.k0);
    s.youngs = youngs_from_constrained(s.modulus, s.poisson);
    steps.push_back(s);
  }
  return steps;
}

namespace {
// Least-squares line y = c0 + c1 x; with one point, the constant through it.
struct Line {
  double c0 = 0.0, c1 = 0.0;
};
Line fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double d = n * sxx - sx * sx;
  if (x.size() < 2 || !(std::abs(d) > 1e-300)) return {sy / n, 0.0};
  const double c1 = (n * sxy - sx * sy) / d;
  return {(sy - c1 * sx) / n, c1};
}
}  // namespace

ElasticEquivalent elastic_equivalent(const std::vector<OedometerState>& path, double stress) {
  const std::vector<OedometerStep> steps = oedometer_steps(path);
  if (steps.empty()) throw Error("oedometric path: at least two states are needed for a modulus");
  if (!(stress > 0.0)) throw Error("oedometric path: the stress level must be > 0 Pa");
  std::vector<double> ls, lm;
  for (const OedometerStep& s : steps) {
    if (!(s.stress > 0.0) || !(s.modulus > 0.0))
      throw Error("oedometric path: a step with sigma_v = " + std::to_string(s.stress) +
                  " Pa and M = " + std::to_string(s.modulus) + " Pa has no power law (both must be > 0)");
    ls.push_back(std::log(s.stress));
    lm.push_back(std::log(s.modulus));
  }
  const Line m = fit_line(ls, lm);
  // Evaluated within the measured range: a stress outside it takes the fit at the nearer end
  // (a power law through a few noisy steps extrapolates badly).
  const double ln_m_at = std::clamp(std::log(stress), *std::min_element(ls.begin(), ls.end()),
                                    *std::max_element(ls.begin(), ls.end()));
  std::vector<double> xs, k0;
  for (const OedometerState& s : path) {
    if (!(s.vertical_stress > 0.0)) continue;
    xs.push_back(std::log(s.vertical_stress));
    k0.push_back(k0_of(s));
  }
  const Line k = fit_line(xs, k0);
  const double ln_k_at = std::clamp(std::log(stress), *std::min_element(xs.begin(), xs.end()),
                                    *std::max_element(xs.begin(), xs.end()));
  ElasticEquivalent e;
  e.stress = stress;
  e.exponent = m.c1;
  e.modulus_stress = std::exp(ln_m_at);
  e.modulus = std::exp(m.c0 + m.c1 * ln_m_at);
  e.k0 = k.c0 + k.c1 * ln_k_at;
  e.poisson = poisson_from_k0(e.k0);
  e.youngs = youngs_from_constrained(e.modulus, e.poisson);
  return e;
}

double hertz_column_strain(double stress, double e_star, double radius, int spheres) {
  const double force = stress * 4.0 * radius * radius;
  const double shortening =
      static_cast<double>(spheres - 1) * hertz::overlap_for_force(e_star, 0.5 * radius, force) +
      2.0 * hertz::overlap_for_force(e_star, radius, force);
  return shortening / (2.0 * radius * static_cast<double>(spheres));
}

double centroid_vertical_strain(double centroid0, double centroid) {
  return 0.75 * (centroid0 - centroid) / centroid0;
}

double hertz_column_centroid(double sphere_weight, double e_star, double radius, int spheres) {
  double z = radius - hertz::overlap_for_force(e_star, radius, spheres * sphere_weight);
  double sum = z;
  for (int k = 0; k + 1 < spheres; ++k) {
    z += 2.0 * radius - hertz::overlap_for_force(e_star, 0.5 * radius, (spheres - 1 - k) * sphere_weight);
    sum += z;
  }
  return sum / static_cast<double>(spheres);
}

}  // namespace upgrain::dem
