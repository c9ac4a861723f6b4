#pragma once
// Ellipsoid pairs for the contact geometry tests: Yan and Regueiro's grain sizes (docs/stress.md), body 1 up
// to 2 m from the origin, random, face-to-face or tip-to-tip orientations, and contacts constructed with a
// known depth and normal (reference::construct_centre2).
#include <cmath>
#include <random>
#include <string>

#include "dem/contact/ellipsoid_geometry.h"
#include "dem/contact/ellipsoid_reference.h"

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

using reference::aligned;
using reference::angle;
using reference::name;
using reference::Orientation;
using reference::random_rotation;
using reference::random_unit;
using Case = reference::ConstructedPair;

// A pair of one of kShapes with a known signed depth (reference::constructed_pair): Yan and Regueiro's
// grain sizes, body 1 1.5-2 m from the origin.
inline Case make_case(std::mt19937_64& rng, const Shape& shape, Orientation o, double delta_over_c) {
  return reference::constructed_pair(rng, shape.ratio, shape.ratio, o, delta_over_c);
}

}  // namespace upgrain::dem::ellipsoid_cases
