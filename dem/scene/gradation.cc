#include "dem/scene/gradation.h"

#include <cmath>
#include <sstream>

#include "dem/core/error.h"

namespace upgrain::dem {

void validate_gradation(const std::vector<GradationPoint>& c) {
  if (c.size() < 2) throw Error("gradation curve needs at least two points (radius, fraction passing)");
  for (std::size_t k = 0; k < c.size(); ++k) {
    std::ostringstream where;
    where << "gradation point " << k + 1 << " (radius " << c[k].radius << ", passing "
          << c[k].fraction_passing << ")";
    if (!(c[k].radius > 0.0)) throw Error(where.str() + ": radius must be positive");
    if (c[k].fraction_passing < 0.0 || c[k].fraction_passing > 1.0)
      throw Error(where.str() + ": fraction passing must lie in [0, 1]");
    if (k > 0 && !(c[k].radius > c[k - 1].radius))
      throw Error(where.str() + ": radii must increase strictly");
    if (k > 0 && c[k].fraction_passing < c[k - 1].fraction_passing)
      throw Error(where.str() + ": fraction passing must not decrease");
  }
  if (c.front().fraction_passing != 0.0)
    throw Error("gradation curve: the first point must have fraction passing 0 (it is the smallest radius)");
  if (c.back().fraction_passing != 1.0)
    throw Error("gradation curve: the last point must have fraction passing 1 (it is the largest radius)");
}

double sampling_acceptance(const std::vector<GradationPoint>& c) {
  validate_gradation(c);
  const double r_min = c.front().radius;
  double acceptance = 0.0;
  for (std::size_t k = 1; k < c.size(); ++k) {
    // r is linear in the fraction passing q over the segment: the integral of (r_min / r)^3 dq.
    const double r0 = c[k - 1].radius, r1 = c[k].radius,
                 dq = c[k].fraction_passing - c[k - 1].fraction_passing;
    const double ratio0 = r_min / r0, ratio1 = r_min / r1;
    acceptance += dq * r_min / (r1 - r0) * 0.5 * (ratio0 * ratio0 - ratio1 * ratio1);
  }
  return acceptance;
}

std::vector<double> sample_radii(const std::vector<GradationPoint>& c, long count, std::mt19937_64& rng) {
  validate_gradation(c);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r_min = c.front().radius;
  std::vector<double> radii;
  radii.reserve(static_cast<std::size_t>(count));
  while (static_cast<long>(radii.size()) < count) {
    const double q = u(rng);
    std::size_t k = 1;
    while (k + 1 < c.size() && c[k].fraction_passing < q) ++k;
    const double f0 = c[k - 1].fraction_passing, f1 = c[k].fraction_passing;
    const double t = f1 > f0 ? (q - f0) / (f1 - f0) : 0.0;
    const double r = c[k - 1].radius + t * (c[k].radius - c[k - 1].radius);
    const double accept = std::pow(r_min / r, 3);
    if (u(rng) <= accept) radii.push_back(r);
  }
  return radii;
}

}  // namespace upgrain::dem
