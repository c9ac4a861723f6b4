#pragma once
// Ellipsoid pairs for the contact geometry tests: the paper's grain sizes, body 1 up to 2 m from
// the origin, random, face-to-face or tip-to-tip orientations, and contacts constructed with a
// known depth and normal (reference::construct_centre2).
#include <cmath>
#include <random>
#include <string>

#include "dem/contact/ellipsoid_geometry.h"
#include "tests/unit/ellipsoid_reference.h"

namespace upgrain::dem::ellipsoid_cases {

#ifdef NDEBUG
constexpr int kScale = 1;
#else
constexpr int kScale = 10;  // -O0 and sanitizer builds: a tenth of the samples
#endif

struct Shape {
  const char* name;
  Vec3 ratio;  // a : b : c
};
inline const Shape kShapes[] = {
    {"1:0.8:0.6", Vec3(1.0, 0.8, 0.6)}, {"1:0.2:0.1", Vec3(1.0, 0.2, 0.1)}, {"1:1:0.1", Vec3(1.0, 1.0, 0.1)}};

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

// A pair with a known signed depth: body 2 placed by reference::construct_centre2 around a
// chosen normal, body 1 up to 2 m from the origin, sizes 1-2.5 mm (the paper's radii).
struct Case {
  Ellipsoid e1, e2;
  reference::V3 normal;   // exact normal
  reference::Real depth;  // exact depth of the rounded (double) configuration
  double c_min;           // smallest semi-axis of the pair
};

inline Case make_case(std::mt19937_64& rng, const Shape& shape, Orientation o, double delta_over_c) {
  std::uniform_real_distribution<double> size(1e-3, 2.5e-3), far(1.5, 2.0);
  Case k;
  const Vec3 n = random_unit(rng);
  k.e1.semi_axes = shape.ratio * size(rng);
  k.e2.semi_axes = shape.ratio * size(rng);
  k.e1.centre = random_unit(rng) * far(rng);
  if (o == Orientation::random) {
    k.e1.orientation = random_rotation(rng);
    k.e2.orientation = random_rotation(rng);
  } else {
    const Vec3 axis = o == Orientation::face_to_face ? Vec3::UnitZ() : Vec3::UnitX();
    k.e1.orientation = aligned(rng, axis, n);
    k.e2.orientation = aligned(rng, axis, -n);
  }
  k.c_min = std::min(k.e1.semi_axes.z(), k.e2.semi_axes.z());
  k.normal = reference::widen(n).normalized();
  const reference::Real delta = static_cast<reference::Real>(delta_over_c) * k.c_min;
  const reference::V3 c2 =
      reference::construct_centre2(reference::body(k.e1), reference::body(k.e2), k.normal, delta);
  k.e2.centre = c2.cast<double>();
  // Rounding c2 to double moves it by e; to first order the depth changes by -n.e (D2), the
  // second-order term is below 1e-30 m.
  k.depth = delta - k.normal.dot(reference::widen(k.e2.centre) - c2);
  return k;
}

inline reference::Real angle(const Vec3& a, const reference::V3& b) {
  const reference::V3 aw = reference::widen(a);
  return std::atan2(aw.cross(b).norm(), aw.dot(b));
}

}  // namespace upgrain::dem::ellipsoid_cases
