#include "dem/analysis/triaxial.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "dem/core/error.h"

namespace upgrain::dem {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The slope of the least-squares line of eps_v against eps_1 over states [first, last).
double rate_ratio(const std::vector<TriaxialState>& path, std::size_t first, std::size_t last) {
  const auto n = static_cast<double>(last - first);
  double mx = 0.0, my = 0.0;
  for (std::size_t k = first; k < last; ++k) {
    mx += path[k].axial_strain;
    my += path[k].volumetric_strain;
  }
  mx /= n;
  my /= n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t k = first; k < last; ++k) {
    const double dx = path[k].axial_strain - mx;
    sxx += dx * dx;
    sxy += dx * (path[k].volumetric_strain - my);
  }
  return sxy / sxx;
}

}  // namespace

double mobilised_friction_angle(double sigma1, double sigma3) {
  if (!(sigma1 + sigma3 > 0.0))
    throw Error("mobilised friction angle: sigma_1 + sigma_3 = " + std::to_string(sigma1 + sigma3) +
                " Pa is not a compression");
  return std::asin(std::clamp((sigma1 - sigma3) / (sigma1 + sigma3), -1.0, 1.0)) / kDegree;
}

double triaxial_dilatancy_angle(double volumetric_rate_ratio) {
  return std::asin(std::clamp(-volumetric_rate_ratio / (2.0 - volumetric_rate_ratio), -1.0, 1.0)) / kDegree;
}

double matsuoka_nakai_angle(double s1, double s2, double s3) {
  if (!(s1 >= s2 && s2 >= s3 && s3 > 0.0))
    throw Error("Matsuoka-Nakai angle: the principal compressions must be ordered and positive, not " +
                std::to_string(s1) + ", " + std::to_string(s2) + ", " + std::to_string(s3));
  const double i1 = s1 + s2 + s3, i2 = s1 * s2 + s2 * s3 + s3 * s1, i3 = s1 * s2 * s3;
  // Triaxial compression (r, 1, 1) with the same invariant j: (r + 2)(2 r + 1) / r = j, so
  // 2 r^2 + (5 - j) r + 2 = 0, its root r >= 1 (j >= 9, the isotropic state's).
  const double j = std::max(i1 * i2 / i3, 9.0);
  const double r = ((j - 5.0) + std::sqrt(std::max((j - 5.0) * (j - 5.0) - 16.0, 0.0))) / 4.0;
  return std::asin((r - 1.0) / (r + 1.0)) / kDegree;
}

double jaky_k0(double friction_angle_deg) { return 1.0 - std::sin(friction_angle_deg * kDegree); }

double inertial_number(double strain_rate, double diameter, double density, double pressure) {
  return strain_rate * diameter * std::sqrt(density / pressure);
}

FrictionStrength friction_strength(const std::vector<TriaxialState>& path, double peak_window,
                                   double critical_share) {
  if (path.size() < 3)
    throw Error("friction angle: a path of " + std::to_string(path.size()) +
                " states; at least 3 are needed");
  if (!(critical_share > 0.0 && critical_share <= 1.0))
    throw Error("friction angle: the critical share must lie in (0, 1]");
  for (std::size_t k = 1; k < path.size(); ++k)
    if (!(path[k].axial_strain > path[k - 1].axial_strain))
      throw Error("friction angle: the axial strain does not grow from state " + std::to_string(k - 1) +
                  " to " + std::to_string(k));
  FrictionStrength f;
  std::vector<double> angle(path.size());
  for (std::size_t k = 0; k < path.size(); ++k)
    angle[k] = mobilised_friction_angle(path[k].axial_stress, path[k].lateral_stress);
  // The peak of the running mean over the window: the largest single state of a noisy path
  // would overstate it.
  std::size_t peak = 0;
  for (std::size_t k = 0, a = 0, b = 0; k < path.size(); ++k) {
    while (path[k].axial_strain - path[a].axial_strain > peak_window) ++a;
    while (b < path.size() && path[b].axial_strain - path[k].axial_strain <= peak_window) ++b;
    double mean = 0.0;
    for (std::size_t j = a; j < b; ++j) mean += angle[j];
    mean /= static_cast<double>(b - a);
    if (k == 0 || mean > f.peak_angle) {
      f.peak_angle = mean;
      peak = k;
    }
  }
  f.peak_strain = path[peak].axial_strain;
  // The states within the window around the peak, widened to three.
  std::size_t first = peak, last = peak + 1;
  while (first > 0 && f.peak_strain - path[first - 1].axial_strain <= peak_window) --first;
  while (last < path.size() && path[last].axial_strain - f.peak_strain <= peak_window) ++last;
  while (last - first < 3) {
    if (first == 0) {
      ++last;
    } else if (last == path.size()) {
      --first;
    } else if (f.peak_strain - path[first - 1].axial_strain <= path[last].axial_strain - f.peak_strain) {
      --first;
    } else {
      ++last;
    }
  }
  f.peak_rate_ratio = rate_ratio(path, first, last);
  f.peak_dilatancy_angle = triaxial_dilatancy_angle(f.peak_rate_ratio);
  // The critical part.
  f.critical_from_strain = (1.0 - critical_share) * path.back().axial_strain;
  std::size_t c = path.size();
  while (c > 0 && path[c - 1].axial_strain >= f.critical_from_strain) --c;
  c = std::min(c, path.size() - 2);  // at least two states for a rate
  f.critical_states = static_cast<int>(path.size() - c);
  double mean = 0.0;
  for (std::size_t k = c; k < path.size(); ++k) mean += angle[k];
  mean /= static_cast<double>(path.size() - c);
  double var = 0.0;
  for (std::size_t k = c; k < path.size(); ++k) var += (angle[k] - mean) * (angle[k] - mean);
  f.critical_angle = mean;
  f.critical_spread = std::sqrt(var / static_cast<double>(path.size() - c));
  f.critical_rate_ratio = rate_ratio(path, c, path.size());
  return f;
}

}  // namespace upgrain::dem
