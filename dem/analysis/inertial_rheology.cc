#include "dem/analysis/inertial_rheology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "dem/core/error.h"

namespace upgrain::dem {

namespace {

void check_points(std::span<const double> x, std::span<const double> y, std::size_t distinct,
                  const char* what) {
  if (x.size() != y.size())
    throw Error(std::string(what) + ": " + std::to_string(x.size()) + " inertial numbers for " +
                std::to_string(y.size()) + " values");
  std::set<double> seen;
  for (double i : x) {
    if (!(i > 0.0) || !std::isfinite(i))
      throw Error(std::string(what) + ": an inertial number must be finite and > 0, not " +
                  std::to_string(i));
    seen.insert(i);
  }
  for (double v : y)
    if (!std::isfinite(v)) throw Error(std::string(what) + ": a value is not finite");
  if (seen.size() < distinct)
    throw Error(std::string(what) + ": " + std::to_string(seen.size()) + " distinct inertial numbers, " +
                std::to_string(distinct) + " needed");
}

// The exact least squares of mu = a (1 - w) + c w for I0 fixed; returns the sum of squares.
double linear_part(std::span<const double> x, std::span<const double> y, double i0, MuOfI& f) {
  double s00 = 0, s01 = 0, s11 = 0, r0 = 0, r1 = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double w = x[k] / (x[k] + i0), u = 1.0 - w;
    s00 += u * u;
    s01 += u * w;
    s11 += w * w;
    r0 += u * y[k];
    r1 += w * y[k];
  }
  const double det = s00 * s11 - s01 * s01;
  if (!(det > 0.0)) return std::numeric_limits<double>::infinity();
  f.mu_s = (s11 * r0 - s01 * r1) / det;
  f.mu_2 = (s00 * r1 - s01 * r0) / det;
  f.i0 = i0;
  double sum = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double e = f(x[k]) - y[k];
    sum += e * e;
  }
  return sum;
}

}  // namespace

MuOfI fit_mu_of_i(std::span<const double> x, std::span<const double> y) {
  check_points(x, y, 3, "the mu(I) fit");
  const auto [lo_it, hi_it] = std::minmax_element(x.begin(), x.end());
  const double lo = std::log(*lo_it / 10.0), hi = std::log(*hi_it * 10.0);
  auto sse = [&](double log_i0) {
    MuOfI f;
    return linear_part(x, y, std::exp(log_i0), f);
  };
  constexpr int kGrid = 400;
  int best = 0;
  double best_sse = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= kGrid; ++k) {
    const double e = sse(lo + (hi - lo) * k / kGrid);
    if (e < best_sse) best_sse = e, best = k;
  }
  // Golden sections over the grid points on either side of the best.
  double a = lo + (hi - lo) * std::max(best - 1, 0) / kGrid;
  double b = lo + (hi - lo) * std::min(best + 1, kGrid) / kGrid;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = sse(c), fd = sse(d);
  for (int k = 0; k < 100 && b - a > 1e-12; ++k) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a), fc = sse(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a), fd = sse(d);
    }
  }
  MuOfI f;
  const double e = linear_part(x, y, std::exp(0.5 * (a + b)), f);
  f.rms = std::sqrt(e / static_cast<double>(x.size()));
  f.i0_at_bound = best == 0 || best == kGrid;
  return f;
}

PhiOfI fit_phi_of_i(std::span<const double> x, std::span<const double> y) {
  check_points(x, y, 2, "the phi(I) fit");
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t k = 0; k < x.size(); ++k) mx += x[k], my += y[k];
  mx /= n, my /= n;
  double sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k)
    sxx += (x[k] - mx) * (x[k] - mx), sxy += (x[k] - mx) * (y[k] - my);
  PhiOfI f;
  f.slope = -sxy / sxx;
  f.phi_max = my + f.slope * mx;
  double e = 0;
  for (std::size_t k = 0; k < x.size(); ++k) e += (f(x[k]) - y[k]) * (f(x[k]) - y[k]);
  f.rms = std::sqrt(e / n);
  return f;
}

}  // namespace upgrain::dem
