#pragma once
// Numbers in report.md: the shortest form with a given count of significant digits; and in the
// studies' CSV tables.
#include <cmath>
#include <cstdio>
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

// A number in a study's CSV table: 9 significant digits; empty when not finite.
inline std::string table_number(double v) {
  if (!std::isfinite(v)) return "";
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

// The grains of a scene in its parameter table, before their size: " spheres, radius " or
// " ellipsoids (a:b:c 1:0.8:0.6, 1:1:1), major semi-axis " (the mix as Particles/shapes writes it).
inline std::string grain_kind(const std::vector<dem::GrainShape>& shapes) {
  if (!dem::has_shapes(shapes)) return " spheres, radius ";
  std::string kind(1, ' ');
  kind += dem::shape_nouns(shapes);
  kind += " (a:b:c";
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    kind += k == 0 ? " " : ", ";
    kind += dem::format_grain_shape(shapes[k], [](double v) { return fmt(v); });
  }
  kind += "), major semi-axis ";
  return kind;
}

}  // namespace upgrain::coupling
