#pragma once
// Rigid planar walls. An open-top box container is a floor and four side planes, each
// with its own Coulomb coefficient (paper brief section 1: friction on/off at walls).
#include <string>
#include <vector>

#include "dem/core/types.h"

namespace upgrain::dem {

struct PlaneWall {
  std::string name;
  Vec3 point;       // a point on the plane
  Vec3 normal;      // unit normal pointing into the granular domain
  double friction;  // Coulomb coefficient particle-wall

  // Signed distance of a point from the plane, positive inside the domain.
  [[nodiscard]] double distance(const Vec3& p) const { return (p - point).dot(normal); }
};

struct BoxContainer {
  double lx = 0.06;     // inner length along x (m), walls at x = 0 and x = lx
  double ly = 0.06;     // inner length along y (m)
  double height = 0.1;  // nominal wall height (m); the planes themselves are unbounded
  // floor, x-, x+, y-, y+
  double friction[5] = {0.5, 0.5, 0.5, 0.5, 0.5};
};

inline std::vector<PlaneWall> make_open_box(const BoxContainer& box) {
  return {
      {"floor", Vec3(0, 0, 0), Vec3(0, 0, 1), box.friction[0]},
      {"wall_x_min", Vec3(0, 0, 0), Vec3(1, 0, 0), box.friction[1]},
      {"wall_x_max", Vec3(box.lx, 0, 0), Vec3(-1, 0, 0), box.friction[2]},
      {"wall_y_min", Vec3(0, 0, 0), Vec3(0, 1, 0), box.friction[3]},
      {"wall_y_max", Vec3(0, box.ly, 0), Vec3(0, -1, 0), box.friction[4]},
  };
}

}  // namespace upgrain::dem
