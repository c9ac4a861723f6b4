// The only translation unit of the driver that includes deal.II: the ParameterHandler
// declarations and the extraction of values, both from the table of sections
// (input/scene_sections.h).
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/patterns.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "coupling/input/prm_syntax.h"
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"
#include "coupling/input/scene_text.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

using dealii::ParameterHandler;
using input::Entry;
using input::Kind;
namespace Patterns = dealii::Patterns;

std::string documentation(const Entry& e) { return e.doc + " [unit: " + e.unit + "]"; }

std::unique_ptr<Patterns::PatternBase> pattern_of(const Entry& e) {
  // Bounds of integer kinds as ints (only theirs: a real's bound, 1e18, is no int).
  auto lo = [&] { return static_cast<int>(e.min); };
  auto hi = [&] { return static_cast<int>(e.max); };
  switch (e.kind) {
    case Kind::real:
      return std::make_unique<Patterns::Double>(e.min, e.max);
    case Kind::integer:
      return std::make_unique<Patterns::Integer>(lo(), hi());
    case Kind::boolean:
      return std::make_unique<Patterns::Bool>();
    case Kind::selection:
      return std::make_unique<Patterns::Selection>(e.choices);
    case Kind::multiple_selection:
      return std::make_unique<Patterns::MultipleSelection>(e.choices);
    case Kind::text:
      return std::make_unique<Patterns::Anything>();
    case Kind::vector3:
      return std::make_unique<Patterns::List>(Patterns::Double(e.min, e.max), 3, 3, ",");
    case Kind::integer3:
      return std::make_unique<Patterns::List>(Patterns::Integer(lo(), hi()), 3, 3, ",");
  }
  return std::make_unique<Patterns::Anything>();
}

void declare(ParameterHandler& prm) {
  SceneInput defaults;
  for (const input::Section& section : input::scene_sections()) {
    prm.enter_subsection(section.name);
    for (const Entry& e : section.entries)
      prm.declare_entry(e.name, e.write(defaults), *pattern_of(e), documentation(e));
    prm.leave_subsection();
  }
}

// An entry's text as its kind converts it (deal.II's conversions: a value its pattern let
// through that does not convert throws).
input::EntryValue value_of(ParameterHandler& prm, const Entry& e) {
  switch (e.kind) {
    case Kind::real:
      return prm.get_double(e.name);
    case Kind::integer:
      return prm.get_integer(e.name);
    case Kind::boolean:
      return prm.get_bool(e.name);
    case Kind::vector3: {
      const auto v = Patterns::Tools::Convert<std::vector<double>>::to_value(
          prm.get(e.name), Patterns::List(Patterns::Double(), 3, 3, ","));
      return std::array<double, 3>{v[0], v[1], v[2]};
    }
    case Kind::integer3: {
      const auto v = Patterns::Tools::Convert<std::vector<int>>::to_value(
          prm.get(e.name), Patterns::List(Patterns::Integer(), 3, 3, ","));
      return std::array<int, 3>{v[0], v[1], v[2]};
    }
    default:
      return prm.get(e.name);
  }
}

SceneInput extract(ParameterHandler& prm, const std::string& source) {
  SceneInput in;
  in.source = source;
  for (const input::Section& section : input::scene_sections()) {
    prm.enter_subsection(section.name);
    for (const Entry& e : section.entries) e.read(in, value_of(prm, e), section.name + "/" + e.name);
    prm.leave_subsection();
  }
  // Every entry, one per line: what a checkpoint stores of the scene (docs/restart.md).
  std::ostringstream all;
  prm.print_parameters(all, ParameterHandler::OutputStyle::ShortPRM);
  in.output.checkpoint.scene = all.str();
  return in;
}

// deal.II's message over several indented lines as one line "<source>:<line>: ...": the text
// was parsed from a string, which deal.II names "input string" or not at all.
std::string one_line_message(const dealii::ExceptionBase& e, const std::string& source) {
  std::ostringstream info;
  e.print_info(info);
  std::string msg;
  for (char c : info.str()) {
    const bool blank = c == ' ' || c == '\n' || c == '\t';
    if (blank && (msg.empty() || msg.back() == ' ')) continue;
    msg += blank ? ' ' : c;
  }
  while (!msg.empty() && msg.back() == ' ') msg.pop_back();
  static const std::regex where(R"(^Line <(\d+)> of file <[^>]*>: *)");
  std::smatch m;
  if (std::regex_search(msg, m, where)) return source + ":" + m[1].str() + ": " + m.suffix().str();
  return source + ": " + (msg.empty() ? "cannot be read" : msg);
}

// "Section/entry" -> value of every `set` line of a parameter text.
std::map<std::string, std::string> set_lines_of(const std::string& text) {
  std::map<std::string, std::string> out;
  std::vector<std::string> sections;
  std::istringstream in(text);
  std::string line;
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  while (std::getline(in, line)) {
    line = trim(line.substr(0, line.find('#')));
    if (line.rfind("subsection ", 0) == 0) {
      sections.push_back(trim(line.substr(11)));
    } else if (line == "end") {
      if (!sections.empty()) sections.pop_back();
    } else if (line.rfind("set ", 0) == 0) {
      const auto eq = line.find('=');
      if (eq == std::string::npos) continue;
      std::string key;
      for (const std::string& s : sections) key += s + "/";
      out[key + trim(line.substr(4, eq - 4))] = trim(line.substr(eq + 1));
    }
  }
  return out;
}

// Two values of an entry alike: the same text, or the same numbers written differently ("1.5e-3"
// and "0.0015": a checkpoint keeps a default as the version that wrote it printed it).
bool same_value(const std::string& a, const std::string& b) {
  if (a == b) return true;
  auto numbers = [](const std::string& text, std::vector<double>& out) {
    std::string item;
    std::istringstream in(text);
    while (in >> item) {
      while (!item.empty() && (item.back() == ',' || item.back() == ';')) item.pop_back();
      if (item.empty()) continue;
      std::size_t used = 0;
      try {
        out.push_back(std::stod(item, &used));
      } catch (const std::exception&) {
        return false;
      }
      if (used != item.size()) return false;
    }
    return true;
  };
  std::vector<double> x, y;
  return numbers(a, x) && numbers(b, y) && !x.empty() && x == y;
}

}  // namespace

SceneInput parse_scene_text(const std::string& bytes, const std::string& source) {
  const std::string text = decode_scene_text(bytes, source);
  check_prm_syntax(text, source);
  ParameterHandler prm;
  declare(prm);
  try {
    prm.parse_input_from_string(text, "", false);
  } catch (const dealii::ExceptionBase& e) {
    throw Error(one_line_message(e, source));
  }
  try {
    return extract(prm, source);
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  } catch (const dealii::ExceptionBase& e) {
    // A value its pattern let through that does not convert (e.g. '0.3{{' for a real).
    throw Error(one_line_message(e, source));
  }
}

std::vector<std::string> differing_parameters(const std::string& run, const std::string& given) {
  const std::map<std::string, std::string> a = set_lines_of(run), b = set_lines_of(given);
  auto may_change = [](const std::string& key) {
    return key == "Simulation/end time" || key == "Simulation/maximum steps" ||
           key.rfind("Checkpoint/", 0) == 0 ||
           (key.rfind("Parallel/", 0) == 0 && key != "Parallel/summation") || key == "Output/folder" ||
           key == "Output/overwrite";
  };
  std::vector<std::string> out;
  for (const auto& [key, value] : a) {
    const auto it = b.find(key);
    const std::string other = it == b.end() ? "(absent)" : it->second;
    if (!same_value(other, value) && !may_change(key))
      out.push_back(key + ": '" + value + "' -> '" + other + "'");
  }
  for (const auto& [key, value] : b)
    if (!a.count(key) && !may_change(key)) out.push_back(key + ": (absent) -> '" + value + "'");
  return out;
}

void apply_material_file(SceneInput& in, const std::string& scene_file) {
  ContinuumOptions& c = in.study.continuum;
  if (c.material_file.empty() || !uses_continuum_material(in)) return;
  std::filesystem::path file(c.material_file);
  if (file.is_relative() && !scene_file.empty())
    file = std::filesystem::path(scene_file).parent_path() / file;
  SceneInput material;
  std::map<std::string, std::string> set;
  try {
    const std::string text = read_scene_bytes(file.string());
    material = parse_scene_text(text, file.string());
    set = set_lines_of(decode_scene_text(text, file.string()));
  } catch (const Error& e) {
    throw Error(in.source + ": Continuum/material file: " + e.what());
  }
  // The file wins for the entries it sets, and only for those (an older file has no strength).
  const ContinuumOptions& m = material.study.continuum;
  const std::pair<const char*, std::pair<double*, double>> entries[] = {
      {"youngs modulus", {&c.youngs_modulus, m.youngs_modulus}},
      {"poisson ratio", {&c.poisson_ratio, m.poisson_ratio}},
      {"friction angle", {&c.friction_angle_deg, m.friction_angle_deg}},
      {"dilatancy angle", {&c.dilatancy_angle_deg, m.dilatancy_angle_deg}}};
  c.material_file_entries.clear();
  for (const auto& [entry, value] : entries)
    if (set.count(std::string("Continuum/") + entry)) {
      *value.first = value.second;
      c.material_file_entries.emplace_back(entry);
    }
  if (c.material_file_entries.empty())
    throw Error(in.source + ": Continuum/material file: " + file.string() +
                " sets none of Continuum/youngs modulus, poisson ratio, friction angle, dilatancy angle");
  c.material_file = file.string();
}

SceneInput read_scene_file(const std::string& filename, const StudyUse& use) {
  SceneInput in = parse_scene_text(read_scene_bytes(filename), filename);
  in.use = use;
  in.scene_folder = std::filesystem::path(filename).parent_path().string();
  apply_material_file(in, filename);
  validate_scene(in);
  return in;
}

SceneInput default_scene(const StudyUse& use) {
  ParameterHandler prm;
  declare(prm);
  SceneInput in = extract(prm, "built-in default scene");
  in.use = use;
  validate_scene(in);
  return in;
}

void print_default_parameters(std::ostream& out) {
  ParameterHandler prm;
  declare(prm);
  out << "# Upgrain scene parameters with their defaults (the built-in default scene).\n"
      << "# Units are given in brackets in each entry's documentation. SI units throughout.\n";
  prm.print_parameters(out, ParameterHandler::OutputStyle::PRM);
}

void print_parameters_markdown(std::ostream& out) {
  out << "# Scene parameters\n\n"
      << "Generated by `upgrain --print-parameters-markdown` from the one table that also "
         "declares them (the sections of `coupling/input/scene_sections.cc`); do not edit by hand.\n\n"
      << "A scene file is a deal.II parameter file: `subsection <Name>`, `set <entry> = <value>`, "
         "`end`; `#` starts a comment. Unknown entries, values out of range and malformed lines "
         "stop the run before anything is written, with the file and line.\n";
  for (const input::Section& section : input::scene_sections()) {
    out << "\n## " << section.name
        << "\n\n| entry | default | allowed | unit | meaning |\n|---|---|---|---|---|\n";
    for (const Entry& p : section.entries) {
      std::ostringstream r;
      switch (p.kind) {
        case Kind::real:
          r << "real in [" << p.min << ", " << p.max << "]";
          break;
        case Kind::integer:
          r << "integer in [" << p.min << ", " << p.max << "]";
          break;
        case Kind::boolean:
          r << "true or false";
          break;
        case Kind::selection:
          r << p.choices;
          break;
        case Kind::text:
          r << "text";
          break;
        case Kind::vector3:
          r << "three reals in [" << p.min << ", " << p.max << "]";
          break;
        case Kind::multiple_selection:
          r << "comma-separated subset of " << p.choices;
          break;
        case Kind::integer3:
          r << "three integers in [" << p.min << ", " << p.max << "]";
          break;
      }
      out << "| `" << p.name << "` | `" << input::default_value(p) << "` | " << r.str() << " | " << p.unit
          << " | " << p.doc << " |\n";
    }
  }
}

}  // namespace upgrain::coupling
