#pragma once
// Containers made of rigid planar walls (dem/core/plane_wall.h). An open-top box is a
// floor and four side planes, each with its own Coulomb coefficient (friction on or off at
// walls, as in Yan and Regueiro's scenes; docs/scenes.md, docs/stress.md).
#include <array>
#include <string>
#include <vector>

#include "dem/core/plane_wall.h"

namespace upgrain::dem {

struct BoxContainer {
  double lx = 0.06;     // inner length along x (m), walls at x = 0 and x = lx
  double ly = 0.06;     // inner length along y (m)
  double height = 0.1;  // nominal wall height (m); the planes themselves are unbounded
  // floor, x-, x+, y-, y+
  double friction[5] = {0.5, 0.5, 0.5, 0.5, 0.5};
  // Yan and Regueiro's constrained collapse: a gate at x = gate_x (0 = none) holds the grains in
  // [0, gate_x] while they are deposited; at gate_open_time it is removed and the bed
  // collapses into the rest of the box. The gate has the x+ wall's friction.
  double gate_x = 0.0;
  double gate_open_time = 0.0;
  // Yan and Regueiro's unconstrained collapse: at side_walls_open_time (0 = never) all four side
  // walls are removed and the bed spreads freely on the floor. The floor is an unbounded
  // plane, so a spreading pile never runs off it.
  double side_walls_open_time = 0.0;
  // The axes along which the container is a periodic cell (docs/periodic.md): [0, lx], [0, ly]
  // and, for z, [0, height]; a periodic axis has no walls on its two faces.
  std::array<bool, 3> periodic{false, false, false};

  [[nodiscard]] bool has_gate() const { return gate_x > 0.0; }
  [[nodiscard]] bool opens_side_walls() const { return side_walls_open_time > 0.0; }
  // The length along x the grains are filled into.
  [[nodiscard]] double fill_length_x() const { return has_gate() ? gate_x : lx; }
};

inline constexpr const char* kGateWallName = "gate";
// The side walls of make_open_box, by name (the unconstrained collapse removes them all).
inline constexpr const char* kSideWallNames[4] = {"wall_x_min", "wall_x_max", "wall_y_min", "wall_y_max"};
inline bool is_side_wall(const std::string& name) {
  for (const char* side : kSideWallNames)
    if (name == side) return true;
  return false;
}

// The floor and the side walls of the bounded axes (a periodic axis has none).
inline std::vector<PlaneWall> make_open_box(const BoxContainer& box) {
  std::vector<PlaneWall> walls;
  if (!box.periodic[2]) walls.push_back({"floor", Vec3(0, 0, 0), Vec3(0, 0, 1), box.friction[0]});
  if (!box.periodic[0]) {
    walls.push_back({kSideWallNames[0], Vec3(0, 0, 0), Vec3(1, 0, 0), box.friction[1]});
    walls.push_back({kSideWallNames[1], Vec3(box.lx, 0, 0), Vec3(-1, 0, 0), box.friction[2]});
  }
  if (!box.periodic[1]) {
    walls.push_back({kSideWallNames[2], Vec3(0, 0, 0), Vec3(0, 1, 0), box.friction[3]});
    walls.push_back({kSideWallNames[3], Vec3(0, box.ly, 0), Vec3(0, -1, 0), box.friction[4]});
  }
  if (box.has_gate())
    walls.push_back({kGateWallName, Vec3(box.gate_x, 0, 0), Vec3(-1, 0, 0), box.friction[2]});
  return walls;
}

}  // namespace upgrain::dem
