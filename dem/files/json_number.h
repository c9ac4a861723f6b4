#pragma once
// A number or a string for a JSON file: JSON (RFC 8259) has no NaN or infinity, so a value that is not
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

// A JSON string with its quotes: '"' and '\\' escaped, control characters as \\u00XX (RFC 8259 §7),
// so that a path or a message with either reads back as written.
inline std::string json_string(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      q += '\\';
      q += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      static const char* hex = "0123456789abcdef";
      q += "\\u00";
      q += hex[(c >> 4) & 0xf];
      q += hex[c & 0xf];
    } else {
      q += c;
    }
  }
  return q + "\"";
}

}  // namespace upgrain::dem::io
