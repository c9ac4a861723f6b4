#pragma once
// The walls of an engine state as columns, one entry per wall: the one list of what a state
// keeps of a wall (docs/restart.md). A checkpoint's walls group holds these columns under
// these names, written in this order (dem/io/engine_state_file.cc), and the restoring
// constructor broadcasts them (simulation_state.cc).
#include <string>
#include <utility>
#include <vector>

#include "dem/core/error.h"
#include "dem/core/plane_wall.h"
#include "dem/engine/engine_state.h"

namespace upgrain::dem {

struct WallColumns {
  std::vector<std::string> names;
  std::vector<Vec3> point, normal;
  std::vector<double> friction;
  std::vector<Vec3> velocity;
  std::vector<Vec3> point_at_build;  // EngineState::wall_points_at_build

  // f(name, column) for each column, in the order above; `c` a WallColumns, const or not.
  template <class Columns, class F>
  static void each(Columns& c, F&& f) {
    f("names", c.names);
    f("point", c.point);
    f("normal", c.normal);
    f("friction", c.friction);
    f("velocity", c.velocity);
    f("point_at_build", c.point_at_build);
  }
};

inline WallColumns wall_columns(const EngineState& s) {
  WallColumns c;
  for (const PlaneWall& w : s.walls) {
    c.names.push_back(w.name);
    c.point.push_back(w.point);
    c.normal.push_back(w.normal);
    c.friction.push_back(w.friction);
    c.velocity.push_back(w.velocity);
  }
  c.point_at_build = s.wall_points_at_build;
  return c;
}

// The walls of `s` from `c`; an Error `where` + "walls differ in count" when its columns do.
inline void set_walls(EngineState& s, WallColumns c, const std::string& where) {
  const std::size_t n = c.names.size();
  if (c.point.size() != n || c.normal.size() != n || c.friction.size() != n || c.velocity.size() != n ||
      c.point_at_build.size() != n)
    throw Error(where + "walls differ in count");
  s.walls.clear();
  for (std::size_t w = 0; w < n; ++w)
    s.walls.push_back({c.names[w], c.point[w], c.normal[w], c.friction[w], c.velocity[w]});
  s.wall_points_at_build = std::move(c.point_at_build);
}

}  // namespace upgrain::dem
