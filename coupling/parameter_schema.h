#pragma once
// Every parameter of a scene file, described once: subsection, name, default, allowed
// values, unit and meaning. From this one table come the ParameterHandler declarations,
// `upgrain --print-parameters`, docs/parameters.md and the unknown-entry diagnostics. The
// contact laws' own parameters come from their table (dem/contact/contact_laws.h).
#include <string>
#include <vector>

namespace upgrain::coupling {

enum class Kind { real, integer, boolean, selection, multiple_selection, text, vector3, integer3 };

struct ParameterSpec {
  std::string section;  // one subsection level
  std::string name;
  std::string default_value;
  Kind kind;
  double min = 0.0;  // inclusive bounds for real and integer kinds
  double max = 0.0;
  std::string choices;  // "a|b" for selection and multiple_selection
  std::string unit;     // SI unit, or "-" for dimensionless
  std::string doc;
};

const std::vector<ParameterSpec>& parameter_schema();

// Names declared in one subsection, for "did you mean" diagnostics.
std::vector<std::string> entries_of(const std::string& section);
std::vector<std::string> sections();

}  // namespace upgrain::coupling
