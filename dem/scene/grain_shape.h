#pragma once
// The shapes of a granular mix: three-axis ellipsoids given by their aspect ratios
// and number fractions. The grain's size (Particles/radius or the gradation) is its major
// semi-axis a, as Yan and Regueiro's radii 1.0-2.5 mm (docs/ellipsoids.md, docs/stress.md).
#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "dem/core/types.h"

namespace upgrain::dem {

struct GrainShape {
  double b_over_a = 1.0;  // 1 >= b/a >= c/a > 0
  double c_over_a = 1.0;
  double number_fraction = 1.0;  // relative weight among the mix's shapes (> 0)

  [[nodiscard]] bool is_sphere() const { return b_over_a == 1.0 && c_over_a == 1.0; }
  [[nodiscard]] Vec3 semi_axes(double a) const { return {a, a * b_over_a, a * c_over_a}; }
};

// Throws upgrain::Error naming the offending shape (1-based) when an aspect ratio is outside
// 1 >= b/a >= c/a > 0 or a fraction is not positive.
void validate_shapes(const std::vector<GrainShape>& shapes);

// True when some shape of the mix is not a sphere.
bool has_ellipsoids(const std::vector<GrainShape>& shapes);

// Shape index of each of n grains: the counts follow the number fractions (largest remainder),
// and the order is a seeded shuffle, so the mix does not depend on the radii.
std::vector<int> assign_shapes(const std::vector<GrainShape>& shapes, long n, std::mt19937_64& rng);

// An orientation uniformly distributed over SO(3) (Shoemake, Graphics Gems III, 1992),
// from the given generator (Eigen's UnitRandom draws from std::rand).
Eigen::Quaterniond random_orientation(std::mt19937_64& rng);

}  // namespace upgrain::dem
