#pragma once
// A parameter a contact law adds to the Contact section of a scene file: the law declares
// it next to its formulas, the driver's schema lists it, and the scene carries its value
// by name (SceneConfig::law_parameters), so a law with its own coefficients needs no other
// file to be read from a scene.

#include <string>

#include "dem/scene/scene_config.h"

namespace upgrain::dem {

struct LawParameter {
  const char* name;           // entry of the Contact section
  const char* default_value;  // as written in a scene file
  double min, max;            // accepted range
  const char* unit;
  const char* doc;
};

// The value of a law's parameter in a scene: as set (SceneConfig::law_parameters), else its
// default.
inline double law_parameter(const SceneConfig& s, const LawParameter& p) {
  for (const NamedValue& v : s.law_parameters)
    if (v.name == p.name) return v.value;
  return std::stod(p.default_value);
}

}  // namespace upgrain::dem
