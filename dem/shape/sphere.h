#pragma once
// The sphere: a grain of one radius, without orientation (its rotation is a kick of omega,
// docs/integrator.md). Its contacts: dem/contact/geometry/pair_geometries.h.
#include <array>
#include <cstddef>

#include "dem/core/particle_store.h"
#include "dem/shape/shape_description.h"

namespace upgrain::dem::shapes {

struct Sphere {
  static constexpr ShapeKind kind = ShapeKind::sphere;
  static constexpr const char* name = "sphere";
  // Its description in the files (shape_description.h): its radius, which every grain has.
  static constexpr std::array<DescriptionColumn, 0> description{};

  // The height of the grain's highest point.
  static double top(const ParticleStore& p, std::size_t i) { return p.x[i].z() + p.radius[i]; }
  // Whether point q lies in the grain.
  static bool contains(const ParticleStore& p, std::size_t i, const Vec3& q) {
    return (q - p.x[i]).squaredNorm() <= p.radius[i] * p.radius[i];
  }
};

}  // namespace upgrain::dem::shapes
