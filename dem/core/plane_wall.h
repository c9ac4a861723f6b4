#pragma once
// A rigid planar wall: the boundary the particles touch (containers are made of them,
// dem/boundary/container.h).
#include <string>

#include "dem/core/types.h"

namespace upgrain::dem {

struct PlaneWall {
  std::string name;
  Vec3 point;       // a point on the plane
  Vec3 normal;      // unit normal pointing into the granular domain
  double friction;  // Coulomb coefficient particle-wall
  // Rigid translation of the wall (m/s): the engine moves `point` by it at every step, and the
  // contacts see it as the wall's velocity (docs/scenes.md, "Moving walls").
  Vec3 velocity = Vec3::Zero();

  // Signed distance of a point from the plane, positive inside the domain.
  [[nodiscard]] double distance(const Vec3& p) const { return (p - point).dot(normal); }
};

}  // namespace upgrain::dem
