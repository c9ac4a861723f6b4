#include "upscale/strain/objective_rates.h"

#include <cmath>

#include "upscale/strain/strain_measures.h"

namespace upgrain::upscale {

std::vector<Mat3> time_derivative(std::span<const double> t, std::span<const Mat3> f) {
  const std::size_t n = f.size();
  std::vector<Mat3> d(n, Mat3::Zero());
  if (n < 2) return d;
  if (n == 2) {  // two-point difference, first order
    d[0] = d[1] = (f[1] - f[0]) / (t[1] - t[0]);
    return d;
  }
  // First output: one-sided three-point formula through t0, t1, t2 (second order).
  {
    const double h1 = t[1] - t[0], h2 = t[2] - t[1];
    d[0] = (-(2.0 * h1 + h2) / (h1 * (h1 + h2))) * f[0] + ((h1 + h2) / (h1 * h2)) * f[1] -
           (h1 / (h2 * (h1 + h2))) * f[2];
  }
  // Interior: central three-point formula for uneven spacing (second order).
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double h1 = t[k] - t[k - 1], h2 = t[k + 1] - t[k];
    d[k] = (-h2 * h2 * f[k - 1] + (h2 * h2 - h1 * h1) * f[k] + h1 * h1 * f[k + 1]) / (h1 * h2 * (h1 + h2));
  }
  // Last output: the mirror image of the first.
  {
    const double h1 = t[n - 2] - t[n - 3], h2 = t[n - 1] - t[n - 2];
    d[n - 1] = (h2 / (h1 * (h1 + h2))) * f[n - 3] - ((h1 + h2) / (h1 * h2)) * f[n - 2] +
               ((h1 + 2.0 * h2) / (h2 * (h1 + h2))) * f[n - 1];
  }
  return d;
}

ObjectiveRates objective_rates(std::span<const double> times, std::span<const Mat3> sigma,
                               std::span<const Mat3> velocity_gradient, std::span<const Mat3> rotation) {
  ObjectiveRates out;
  const std::size_t n = times.size();
  if (sigma.size() != n || velocity_gradient.size() != n || (!rotation.empty() && rotation.size() != n)) {
    out.reason = "series lengths differ (times " + std::to_string(n) + ", stress " +
                 std::to_string(sigma.size()) + ", L " + std::to_string(velocity_gradient.size()) + ", R " +
                 std::to_string(rotation.size()) + ")";
    return out;
  }
  if (n < 2) {
    out.reason = "fewer than 2 outputs: no time derivative";
    return out;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const bool finite = std::isfinite(times[k]) && sigma[k].allFinite() && velocity_gradient[k].allFinite() &&
                        (rotation.empty() || rotation[k].allFinite());
    if (!finite) {
      out.reason = "non-finite value at output " + std::to_string(k);
      return out;
    }
    if (k > 0 && !(times[k] > times[k - 1])) {
      out.reason = "output times not strictly increasing at output " + std::to_string(k);
      return out;
    }
  }

  out.valid = true;
  out.sigma_dot = time_derivative(times, sigma);
  std::vector<Mat3> r_dot;
  if (!rotation.empty()) r_dot = time_derivative(times, rotation);
  for (std::size_t k = 0; k < n; ++k) {
    const Mat3& s = sigma[k];
    const Mat3& l = velocity_gradient[k];
    out.jaumann.push_back(jaumann_rate(out.sigma_dot[k], s, spin(l)));
    out.truesdell.push_back(truesdell_rate(out.sigma_dot[k], s, l));
    out.oldroyd.push_back(oldroyd_rate(out.sigma_dot[k], s, l));
    if (!rotation.empty()) {
      // R_dot R^T is skew for the exact R_dot (d/dt R R^T = 0); differencing leaves an O(h^2)
      // symmetric part, removed here.
      const Mat3 omega = spin(r_dot[k] * rotation[k].transpose());
      out.green_naghdi.push_back(green_naghdi_rate(out.sigma_dot[k], s, omega));
    }
  }
  return out;
}

}  // namespace upgrain::upscale
