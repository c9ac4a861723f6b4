#pragma once
// The three-axis ellipsoid: semi-axes a >= b >= c along its body axes, an orientation, and the
// principal moments of a solid ellipsoid (docs/ellipsoids.md). Its contacts:
// dem/contact/geometry/pair_geometries.h.
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <span>

#include "dem/core/particle_store.h"
#include "dem/shape/shape_description.h"

namespace upgrain::dem::shapes {

struct Ellipsoid {
  static constexpr ShapeKind kind = ShapeKind::ellipsoid;
  static constexpr const char* name = "ellipsoid";
  // Its description in the files (shape_description.h); its orientation and principal moments
  // are those of every shape but the sphere.
  static constexpr DescriptionColumn description[] = {
      {"semi_axes", &ParticleStore::semi_axes, "a, b, c (m), a >= b >= c along the body x, y, z axes"}};

  // The height of the grain's highest point: its support along z, sqrt(e_z^T M e_z) with
  // M = R diag(a^2, b^2, c^2) R^T.
  static double top(const ParticleStore& p, std::size_t i) {
    const Vec3 ez_body = p.orientation[i].conjugate() * Vec3::UnitZ();
    return p.x[i].z() + ez_body.cwiseProduct(p.semi_axes[i]).norm();
  }
  // Whether point q lies in the grain: sum (y_k / a_k)^2 <= 1 in the body frame, after the
  // bounding sphere.
  static bool contains(const ParticleStore& p, std::size_t i, const Vec3& q) {
    const Vec3 d = q - p.x[i];
    if (d.squaredNorm() > p.radius[i] * p.radius[i]) return false;
    const Vec3 y = p.orientation[i].conjugate() * d;
    return y.cwiseQuotient(p.semi_axes[i]).squaredNorm() <= 1.0;
  }

  // In a scene's mix (dem/scene/grain_shape.h): its size is a, its ratios b/a and c/a.
  static constexpr std::array<const char*, 2> ratios{"b/a", "c/a"};
  static constexpr const char* rule = "1 >= b/a >= c/a > 0";
  static bool valid(std::span<const double> r) { return r[0] <= 1.0 && r[1] <= r[0] && r[1] > 0.0; }
  // The thinnest half-thickness c, the flattest point (the Gaussian radius a b / c at the c
  // pole) and the volume 4/3 pi a b c, each over the sphere's of radius a.
  static ShapeScales scales(std::span<const double> r) { return {r[1], r[0] / r[1], r[0] * r[1]}; }
  static void add(ParticleStore& p, GlobalId id, double a, std::span<const double> r, double density,
                  const Eigen::Quaterniond& orientation, const GrainMotion& m) {
    p.add_ellipsoid(id, {Vec3(a, a * r[0], a * r[1]), density, orientation}, m);
  }
  static void ratios_of(const ParticleStore& p, std::size_t i, std::span<double> out) {
    const Vec3& ax = p.semi_axes[i];
    out[0] = ax.y() / ax.x();
    out[1] = ax.z() / ax.x();
  }
};

}  // namespace upgrain::dem::shapes
