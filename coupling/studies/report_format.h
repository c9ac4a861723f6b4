#pragma once
// Numbers in report.md: the shortest form with a given count of significant digits.
#include <sstream>
#include <string>
#include <vector>

#include "dem/scene/grain_shape.h"

namespace upgrain::coupling {

inline std::string fmt(double v, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

// The grains of a scene in its parameter table, before their size: " spheres, radius " or
// " ellipsoids (a:b:c 1:0.8:0.6, 1:1:1), major semi-axis ".
inline std::string grain_kind(const std::vector<dem::GrainShape>& shapes) {
  if (!dem::has_ellipsoids(shapes)) return " spheres, radius ";
  std::string kind = " ellipsoids (a:b:c";
  for (std::size_t k = 0; k < shapes.size(); ++k)
    kind += (k == 0 ? " 1:" : ", 1:") + fmt(shapes[k].b_over_a) + ":" + fmt(shapes[k].c_over_a);
  return kind + "), major semi-axis ";
}

}  // namespace upgrain::coupling
