#pragma once
// Numbers in report.md: the shortest form with a given count of significant digits.
#include <sstream>
#include <string>

namespace upgrain::coupling {

inline std::string fmt(double v, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace upgrain::coupling
