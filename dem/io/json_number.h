#pragma once
// A number for a JSON file: JSON (RFC 8259) has no NaN or infinity, so a value that is not
// finite (an energy ratio without gravity, a relative error of a zero field) is written null,
// which every JSON reader takes; finite ones with 17 digits, so they read back bitwise.
#include <cmath>
#include <sstream>
#include <string>

namespace upgrain::dem::io {

inline std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

}  // namespace upgrain::dem::io
