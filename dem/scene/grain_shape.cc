#include "dem/scene/grain_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <sstream>

#include "dem/core/error.h"

namespace upgrain::dem {

void validate_shapes(const std::vector<GrainShape>& shapes) {
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const GrainShape& s = shapes[k];
    if (!(s.b_over_a <= 1.0 && s.c_over_a <= s.b_over_a && s.c_over_a > 0.0) ||
        !(s.number_fraction > 0.0 && std::isfinite(s.number_fraction))) {
      std::ostringstream m;
      m << "shape " << k + 1 << " (1:" << s.b_over_a << ":" << s.c_over_a << ", fraction "
        << s.number_fraction << ") needs 1 >= b/a >= c/a > 0 and a positive fraction";
      throw Error(m.str());
    }
  }
}

bool has_ellipsoids(const std::vector<GrainShape>& shapes) {
  return std::any_of(shapes.begin(), shapes.end(), [](const GrainShape& s) { return !s.is_sphere(); });
}

std::vector<int> assign_shapes(const std::vector<GrainShape>& shapes, long n, std::mt19937_64& rng) {
  std::vector<int> index(static_cast<std::size_t>(n), 0);
  if (shapes.size() < 2) return index;
  double total = 0.0;
  for (const GrainShape& s : shapes) total += s.number_fraction;
  // Largest remainder: floor of each share, the rest to the largest fractional parts.
  std::vector<long> count(shapes.size());
  std::vector<std::pair<double, std::size_t>> remainder(shapes.size());
  long given = 0;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const double share = n * shapes[k].number_fraction / total;
    count[k] = static_cast<long>(std::floor(share));
    remainder[k] = {share - count[k], k};
    given += count[k];
  }
  std::stable_sort(remainder.begin(), remainder.end(), [](auto& a, auto& b) { return a.first > b.first; });
  for (long r = 0; r < n - given; ++r) ++count[remainder[static_cast<std::size_t>(r)].second];
  std::size_t at = 0;
  for (std::size_t k = 0; k < shapes.size(); ++k)
    for (long c = 0; c < count[k]; ++c) index[at++] = static_cast<int>(k);
  std::shuffle(index.begin(), index.end(), rng);
  return index;
}

Eigen::Quaterniond random_orientation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double u1 = u(rng), u2 = 2.0 * std::numbers::pi * u(rng), u3 = 2.0 * std::numbers::pi * u(rng);
  const double s1 = std::sqrt(1.0 - u1), s2 = std::sqrt(u1);
  return Eigen::Quaterniond(s2 * std::cos(u3), s1 * std::sin(u2), s1 * std::cos(u2), s2 * std::sin(u3));
}

}  // namespace upgrain::dem
