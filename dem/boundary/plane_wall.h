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
  // The paper's constrained collapse: a gate at x = gate_x (0 = none) holds the grains in
  // [0, gate_x] while they are deposited; at gate_open_time it is removed and the bed
  // collapses into the rest of the box. The gate has the x+ wall's friction.
  double gate_x = 0.0;
  double gate_open_time = 0.0;

  [[nodiscard]] bool has_gate() const { return gate_x > 0.0; }
  // The length along x the grains are filled into.
  [[nodiscard]] double fill_length_x() const { return has_gate() ? gate_x : lx; }
};

inline constexpr const char* kGateWallName = "gate";

inline std::vector<PlaneWall> make_open_box(const BoxContainer& box) {
  std::vector<PlaneWall> walls = {
      {"floor", Vec3(0, 0, 0), Vec3(0, 0, 1), box.friction[0]},
      {"wall_x_min", Vec3(0, 0, 0), Vec3(1, 0, 0), box.friction[1]},
      {"wall_x_max", Vec3(box.lx, 0, 0), Vec3(-1, 0, 0), box.friction[2]},
      {"wall_y_min", Vec3(0, 0, 0), Vec3(0, 1, 0), box.friction[3]},
      {"wall_y_max", Vec3(0, box.ly, 0), Vec3(0, -1, 0), box.friction[4]},
  };
  if (box.has_gate())
    walls.push_back({kGateWallName, Vec3(box.gate_x, 0, 0), Vec3(-1, 0, 0), box.friction[2]});
  return walls;
}

}  // namespace upgrain::dem
