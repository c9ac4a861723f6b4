#pragma once
// When the collapse scenes take walls out of the box (docs/scenes.md): the constrained
// collapse removes the gate at gate_open_time, the unconstrained collapse removes all four
// side walls at side_walls_open_time. A plain schedule, so the run loop and the tests
// share it; the removal itself is Simulation::remove_wall, which rebuilds the neighbour
// and wall lists, so no list refers to a removed wall afterwards.
#include <string>
#include <utility>
#include <vector>

#include "dem/boundary/container.h"

namespace upgrain::dem {

struct WallRelease {
  double time = 0.0;               // s of simulated time
  std::vector<std::string> walls;  // names, as in make_open_box
};

// The releases of a container, in time order (empty for a plain box).
inline std::vector<WallRelease> wall_releases(const BoxContainer& box) {
  std::vector<WallRelease> r;
  if (box.has_gate()) r.push_back({box.gate_open_time, {kGateWallName}});
  if (box.opens_side_walls())
    r.push_back({box.side_walls_open_time,
                 {kSideWallNames[0], kSideWallNames[1], kSideWallNames[2], kSideWallNames[3]}});
  if (r.size() == 2 && r[1].time < r[0].time) std::swap(r[0], r[1]);
  return r;
}

}  // namespace upgrain::dem
