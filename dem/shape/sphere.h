#pragma once
// The sphere: a grain of one radius, without orientation (its rotation is a kick of omega,
// docs/integrator.md). Its contacts: dem/contact/geometry/pair_geometries.h.
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <span>

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

  // In a scene's mix (dem/scene/grain_shape.h): its size is its radius, and nothing else.
  static constexpr std::array<const char*, 0> ratios{};
  static constexpr const char* rule = "";
  static bool valid(std::span<const double> /*ratios*/) { return true; }
  static ShapeScales scales(std::span<const double> /*ratios*/) { return {}; }
  static void add(ParticleStore& p, GlobalId id, double a, std::span<const double> /*ratios*/, double density,
                  const Eigen::Quaterniond& /*orientation*/, const GrainMotion& m) {
    p.add_sphere(id, a, density, m.x, m.v, m.omega);
  }
  static void ratios_of(const ParticleStore& /*p*/, std::size_t /*i*/, std::span<double> /*out*/) {}
};

}  // namespace upgrain::dem::shapes
