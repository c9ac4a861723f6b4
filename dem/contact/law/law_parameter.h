#pragma once
// A parameter a contact law adds to the Contact section of a scene file: the law declares
// it next to its formulas, the driver's schema lists it, and the scene carries its value
// by name (SceneConfig::law_parameters), so a law with its own coefficients needs no other
// file to be read from a scene. The law sees only those values, not the scene: contact/ lies
// below scene/ (docs/architecture.md, "Folders").

#include <span>
#include <string>

namespace upgrain::dem {

// A parameter of the scene's contact law, by the name the law declares.
struct NamedValue {
  std::string name;
  double value;
};

struct LawParameter {
  const char* name;           // entry of the Contact section
  const char* default_value;  // as written in a scene file
  double min, max;            // accepted range
  const char* unit;
  const char* doc;
};

// The value of a law's parameter among a scene's `values` (SceneConfig::law_parameters): as
// set, else its default.
inline double law_parameter(std::span<const NamedValue> values, const LawParameter& p) {
  for (const NamedValue& v : values)
    if (v.name == p.name) return v.value;
  return std::stod(p.default_value);
}

}  // namespace upgrain::dem
