// The only translation unit of the driver that includes deal.II: the ParameterHandler
// declarations and the extraction of values into plain structs.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "coupling/parameter_schema.h"
#include "coupling/prm_syntax.h"
#include "coupling/scene_input.h"
#include "coupling/scene_text.h"
#include "dem/contact/contact_laws.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

namespace {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

std::string documentation(const ParameterSpec& p) { return p.doc + " [unit: " + p.unit + "]"; }

void declare(ParameterHandler& prm) {
  for (const std::string& section : sections()) {
    prm.enter_subsection(section);
    for (const ParameterSpec& p : parameter_schema()) {
      if (p.section != section) continue;
      switch (p.kind) {
        case Kind::real:
          prm.declare_entry(p.name, p.default_value, Patterns::Double(p.min, p.max), documentation(p));
          break;
        case Kind::integer:
          prm.declare_entry(p.name, p.default_value,
                            Patterns::Integer(static_cast<int>(p.min), static_cast<int>(p.max)),
                            documentation(p));
          break;
        case Kind::boolean:
          prm.declare_entry(p.name, p.default_value, Patterns::Bool(), documentation(p));
          break;
        case Kind::selection:
          prm.declare_entry(p.name, p.default_value, Patterns::Selection(p.choices), documentation(p));
          break;
        case Kind::text:
          prm.declare_entry(p.name, p.default_value, Patterns::Anything(), documentation(p));
          break;
        case Kind::vector3:
          prm.declare_entry(p.name, p.default_value,
                            Patterns::List(Patterns::Double(p.min, p.max), 3, 3, ","), documentation(p));
          break;
        case Kind::multiple_selection:
          prm.declare_entry(p.name, p.default_value, Patterns::MultipleSelection(p.choices),
                            documentation(p));
          break;
        case Kind::integer3:
          prm.declare_entry(
              p.name, p.default_value,
              Patterns::List(Patterns::Integer(static_cast<int>(p.min), static_cast<int>(p.max)), 3, 3, ","),
              documentation(p));
          break;
      }
    }
    prm.leave_subsection();
  }
}

std::vector<dem::GradationPoint> parse_gradation(const std::string& text) {
  std::vector<dem::GradationPoint> curve;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    const auto colon = item.find(':');
    dem::GradationPoint p{};
    std::istringstream r(colon == std::string::npos ? "" : item.substr(0, colon));
    std::istringstream f(colon == std::string::npos ? "" : item.substr(colon + 1));
    std::string rest_r, rest_f;
    if (colon == std::string::npos || !(r >> p.radius) || (r >> rest_r) || !(f >> p.fraction_passing) ||
        (f >> rest_f))
      throw Error("Particles/gradation: cannot read the point '" + item +
                  "'; write 'radius:fraction passing' pairs separated by commas, e.g. '1e-3:0, 2.5e-3:1'");
    curve.push_back(p);
  }
  return curve;
}

// "1:0.8:0.6@0.5, 1:0.6:0.4" -> shapes with aspect ratios and number fractions.
std::vector<dem::GrainShape> parse_shapes(const std::string& text) {
  std::vector<dem::GrainShape> shapes;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    const auto at = item.find('@');
    std::string ratios = item.substr(0, at);
    for (char& c : ratios)
      if (c == ':') c = ' ';
    std::istringstream r(ratios);
    double a = 0.0;
    dem::GrainShape shape;
    std::string rest;
    bool ok = static_cast<bool>(r >> a >> shape.b_over_a >> shape.c_over_a) && !(r >> rest) && a > 0.0;
    if (ok && at != std::string::npos) {
      std::istringstream f(item.substr(at + 1));
      ok = static_cast<bool>(f >> shape.number_fraction) && !(f >> rest);
    }
    if (!ok)
      throw Error("Particles/shapes: cannot read the shape '" + item +
                  "'; write aspect ratios 'a:b:c' with an optional '@fraction', separated by commas, "
                  "e.g. '1:0.8:0.6, 1:0.6:0.4@2'");
    // Ratios to a (a:b:c may be given in any unit, e.g. 10:8:6).
    shape.b_over_a /= a;
    shape.c_over_a /= a;
    shapes.push_back(shape);
  }
  return shapes;
}

// The items of a list separated by `separator`, trimmed; empty items left out.
std::vector<std::string> split_list(const std::string& text, char separator = ',') {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, separator)) {
    const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
  }
  return out;
}

// Numbers of a list; throws upgrain::Error naming `entry` and the item that is not a finite number.
std::vector<double> numbers_of(const std::string& text, const std::string& entry, char separator = ',') {
  std::vector<double> out;
  for (const std::string& item : split_list(text, separator)) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !std::isfinite(v)) throw Error(entry + ": '" + item + "' is not a number");
    out.push_back(v);
  }
  return out;
}

SceneInput extract(ParameterHandler& prm, const std::string& source) {
  SceneInput in;
  in.source = source;
  dem::SceneConfig& s = in.scene;
  prm.enter_subsection("Simulation");
  s.time_step = prm.get_double("time step");
  s.end_time = prm.get_double("end time");
  in.maximum_steps = prm.get_double("maximum steps");
  in.control.rest_ratio = prm.get_double("stop at rest ratio");
  in.control.rest_window = prm.get_double("stop at rest window");
  s.time_step_rule.rayleigh_fraction = prm.get_double("Rayleigh fraction");
  s.time_step_rule.hertz_fraction = prm.get_double("Hertz fraction");
  s.time_step_rule.impact_speed = prm.get_double("expected impact speed");
  s.time_step_rule.allow_unsafe = prm.get_bool("allow unsafe time step");
  s.neighbor_skin = prm.get_double("neighbor skin");
  prm.leave_subsection();

  prm.enter_subsection("Effects");
  {
    auto sw = [&](const char* name) {
      return dem::parse_effect_switch(prm.get(name), std::string("Effects/") + name);
    };
    dem::EffectSwitches& e = in.effect_switches;
    e.gravity = sw("gravity");
    e.friction = sw("tangential friction");
    e.damping = sw("damping");
    e.wall_friction = sw("wall friction");
    e.rotation = sw("rotation");
    e.energy_tracking = sw("energy tracking");
    e.rolling_resistance = sw("rolling resistance");
    e.twisting_resistance = sw("twisting resistance");
  }
  s.gravity = prm.get_double("gravity acceleration");
  prm.leave_subsection();

  prm.enter_subsection("Particles");
  s.particles.count = prm.get_integer("count");
  s.particles.radius = prm.get_double("radius");
  s.particles.gradation = parse_gradation(prm.get("gradation"));
  s.particles.shapes = parse_shapes(prm.get("shapes"));
  in.initial_packing = prm.get("initial packing");
  s.particles.material.density = prm.get_double("density");
  s.particles.material.youngs_modulus = prm.get_double("youngs modulus");
  s.particles.material.poisson_ratio = prm.get_double("poisson ratio");
  prm.leave_subsection();

  prm.enter_subsection("Contact");
  s.friction = prm.get_double("friction coefficient");
  s.damping_ratio = prm.get_double("damping ratio");
  s.rolling_friction = prm.get_double("rolling friction coefficient");
  s.rolling_damping_ratio = prm.get_double("rolling damping ratio");
  s.contact_solver.gradient_tolerance = prm.get_double("solver gradient tolerance");
  s.contact_solver.max_iterations = static_cast<int>(prm.get_integer("solver iterations"));
  s.contact_law = prm.get("law");
  for (const dem::LawInfo& law : dem::contact_law_table())
    for (const dem::LawParameter& p : law.parameters)
      if (law.name == s.contact_law) s.law_parameters.push_back({p.name, prm.get_double(p.name)});
  prm.leave_subsection();

  prm.enter_subsection("Container");
  s.container.lx = prm.get_double("length x");
  s.container.ly = prm.get_double("length y");
  s.container.height = prm.get_double("height");
  s.container.friction[0] = prm.get_double("floor friction");
  s.container.friction[1] = prm.get_double("wall x min friction");
  s.container.friction[2] = prm.get_double("wall x max friction");
  s.container.friction[3] = prm.get_double("wall y min friction");
  s.container.friction[4] = prm.get_double("wall y max friction");
  s.container.gate_x = prm.get_double("gate x");
  s.container.gate_open_time = prm.get_double("gate open time");
  in.collapse = prm.get("collapse");
  s.container.side_walls_open_time = prm.get_double("side walls open time");
  prm.leave_subsection();

  prm.enter_subsection("Fill");
  s.fill.method = prm.get("method") == "random" ? dem::FillMethod::random : dem::FillMethod::lattice;
  s.fill.bottom_gap = prm.get_double("bottom gap");
  s.fill.lattice_spacing = prm.get_double("lattice spacing");
  s.fill.position_jitter = prm.get_double("position jitter");
  s.fill.solid_fraction = prm.get_double("solid fraction");
  {
    const auto v = Patterns::Tools::Convert<std::vector<double>>::to_value(
        prm.get("initial velocity"), Patterns::List(Patterns::Double(), 3, 3, ","));
    s.fill.velocity = dem::Vec3(v[0], v[1], v[2]);
  }
  s.fill.velocity_jitter = prm.get_double("velocity jitter");
  s.fill.seed = static_cast<std::uint64_t>(prm.get_integer("seed"));
  prm.leave_subsection();

  prm.enter_subsection("Insertion");
  {
    auto vector3 = [&](const char* name) {
      const auto v = Patterns::Tools::Convert<std::vector<double>>::to_value(
          prm.get(name), Patterns::List(Patterns::Double(), 3, 3, ","));
      return dem::Vec3(v[0], v[1], v[2]);
    };
    dem::InsertionSpec& ins = s.insertion;
    ins.count = prm.get_integer("count");
    ins.rate = prm.get_double("rate");
    ins.mass_rate = prm.get_double("mass rate");
    ins.start_time = prm.get_double("start time");
    ins.interval = prm.get_double("interval");
    ins.inlet_lo = vector3("inlet min");
    ins.inlet_hi = vector3("inlet max");
    ins.velocity = vector3("velocity");
  }
  prm.leave_subsection();

  prm.enter_subsection("Lid");
  {
    LidControl& lid = in.control.lid;
    const std::string mode = prm.get("mode");
    lid.mode = mode == "velocity" ? LidControl::Mode::velocity
               : mode == "servo"  ? LidControl::Mode::servo
                                  : LidControl::Mode::none;
    lid.place_time = prm.get_double("place time");
    lid.gap = prm.get_double("gap");
    lid.friction = prm.get_double("friction");
    lid.speed = prm.get_double("speed");
    lid.target_stresses = numbers_of(prm.get("target stresses"), "Lid/target stresses");
    lid.step_duration = prm.get_double("step duration");
    lid.gain_factor = prm.get_double("gain factor");
    lid.max_speed = prm.get_double("max speed");
    lid.update_every = prm.get_integer("update interval");
  }
  prm.leave_subsection();

  prm.enter_subsection("Calibration");
  {
    CalibrationOptions& c = in.calibration;
    c.oedometer_by_lid = prm.get("oedometer loading") == "lid";
    c.gravity_factors = numbers_of(prm.get("gravity factors"), "Calibration/gravity factors");
    c.lid_stress_factors = numbers_of(prm.get("lid stresses"), "Calibration/lid stresses");
    c.hold_time = prm.get_double("hold time");
    c.seating_time = prm.get_double("seating time");
    c.gain_factor = prm.get_double("gain factor");
    c.max_speed = prm.get_double("max speed");
    c.update_every = prm.get_integer("update interval");
    c.side_wall_friction = prm.get_double("side wall friction");
    c.confining_stress_factor = prm.get_double("confining stress");
    c.axial_strain_rate = prm.get_double("axial strain rate");
    c.final_axial_strain = prm.get_double("final axial strain");
    c.consolidation_time = prm.get_double("consolidation time");
    c.critical_state_strength = prm.get("continuum strength") == "critical state";
  }
  prm.leave_subsection();

  prm.enter_subsection("Output");
  in.output.folder = prm.get("folder");
  in.overwrite = prm.get_bool("overwrite");
  in.output.snapshot_interval = prm.get_double("snapshot interval");
  in.output.series_interval = prm.get_double("time series interval");
  in.output.energy_balance = prm.get_bool("energy balance");
  in.output.force_network = prm.get_bool("force network");
  prm.leave_subsection();

  prm.enter_subsection("Accuracy");
  {
    AccuracyOptions& a = in.accuracy;
    a.knobs = split_list(prm.get("knobs"));
    a.time_step_fractions = numbers_of(prm.get("time step fractions"), "Accuracy/time step fractions");
    a.modulus_factors = numbers_of(prm.get("modulus factors"), "Accuracy/modulus factors");
    a.skins = numbers_of(prm.get("skins"), "Accuracy/skins");
    a.relaxation_tolerances = numbers_of(prm.get("relaxation tolerances"), "Accuracy/relaxation tolerances");
    a.solver_tolerances = numbers_of(prm.get("solver tolerances"), "Accuracy/solver tolerances");
    a.solver_iteration_caps = numbers_of(prm.get("solver iteration caps"), "Accuracy/solver iteration caps");
    for (const std::string& g : split_list(prm.get("grids"), ';')) {
      const std::vector<double> n = numbers_of(g, "Accuracy/grids", ' ');
      if (n.size() != 3) throw Error("Accuracy/grids: '" + g + "' is not three cell counts");
      a.grids.push_back({static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2])});
    }
    for (double d : numbers_of(prm.get("fem degrees"), "Accuracy/fem degrees"))
      a.fem_degrees.push_back(static_cast<unsigned>(d));
    for (double r : numbers_of(prm.get("fem refinements"), "Accuracy/fem refinements"))
      a.fem_refinements.push_back(static_cast<unsigned>(r));
    a.replicas = static_cast<int>(prm.get_integer("replicas"));
    a.tolerance = prm.get_double("tolerance");
  }
  prm.leave_subsection();

  prm.enter_subsection("Checkpoint");
  in.output.checkpoint.interval = prm.get_double("interval");
  in.output.checkpoint.wall_interval = prm.get_double("wall interval");
  in.output.checkpoint.keep = static_cast<int>(prm.get_integer("keep"));
  prm.leave_subsection();

  prm.enter_subsection("Parallel");
  {
    in.parallel.summation =
        prm.get("summation") == "fast" ? dem::Summation::fast : dem::Summation::deterministic;
    in.parallel.legacy_engine = prm.get("DEM engine");
    const auto b = Patterns::Tools::Convert<std::vector<int>>::to_value(
        prm.get("blocks"), Patterns::List(Patterns::Integer(0, 4096), 3, 3, ","));
    for (int d = 0; d < 3; ++d) in.parallel.blocks[d] = b[d];
    in.parallel.balance_interval = prm.get_double("balance interval");
    in.parallel.balance_by_pairs = prm.get("balance cost") == "pair slots";
  }
  prm.leave_subsection();

  prm.enter_subsection("Stress");
  dem::io::GridStressOptions& gs = in.output.grid_stress;
  for (const std::string& name : dealii::Utilities::split_string_list(prm.get("formulas"), ',')) {
    const auto f = dem::stress_formula_from_name(name);
    if (f && std::find(gs.formulas.begin(), gs.formulas.end(), *f) == gs.formulas.end())
      gs.formulas.push_back(*f);
  }
  {
    const auto n = Patterns::Tools::Convert<std::vector<int>>::to_value(
        prm.get("grid cells"), Patterns::List(Patterns::Integer(1, 1000), 3, 3, ","));
    for (int d = 0; d < 3; ++d) gs.cells[d] = n[d];
  }
  in.stress_box = prm.get("box");
  gs.interval = prm.get_double("interval");
  prm.leave_subsection();

  prm.enter_subsection("Strain");
  {
    upscale::GridStrainOutputOptions& st = in.output.grid_strain;
    st.enabled = prm.get_bool("enabled");
    st.reference_time = prm.get_double("reference time");
    st.kernel.set =
        prm.get("set") == "eulerian" ? upscale::StrainSet::eulerian : upscale::StrainSet::lagrangian;
    if (const auto f = dem::stress_formula_from_name(prm.get("rate formula"))) st.rate_formula = *f;
    st.kernel.definitions = {false, false};
    for (const std::string& name : dealii::Utilities::split_string_list(prm.get("definitions"), ','))
      st.kernel.definitions[static_cast<int>(name == "tessellation" ? upscale::StrainDefinition::tessellation
                                                                    : upscale::StrainDefinition::best_fit)] =
          true;
  }
  prm.leave_subsection();

  prm.enter_subsection("Study");
  in.study.compare_with_continuum = prm.get_bool("compare with continuum");
  for (const std::string& name : dealii::Utilities::split_string_list(prm.get("comparison formulas"), ',')) {
    const auto f = dem::stress_formula_from_name(name);
    if (f && std::find(in.study.formulas.begin(), in.study.formulas.end(), *f) == in.study.formulas.end())
      in.study.formulas.push_back(*f);
  }
  in.control.relax_at_end = prm.get_bool("relax at end");
  in.control.relaxation.force_tolerance = prm.get_double("relaxation tolerance");
  in.control.relaxation.max_steps = prm.get_integer("max relaxation steps");
  prm.leave_subsection();

  prm.enter_subsection("CoarseGraining");
  {
    CoarseGrainingOptions& cg = in.study.coarse_graining;
    cg.density = cg.velocity = cg.stress = cg.wall_force_density = cg.displacement = cg.momentum_balance =
        false;
    for (const std::string& name : dealii::Utilities::split_string_list(prm.get("fields"), ',')) {
      cg.density |= name == "density";
      cg.velocity |= name == "velocity";
      cg.stress |= name == "stress";
      cg.wall_force_density |= name == "wall force density";
      cg.displacement |= name == "displacement";
      cg.momentum_balance |= name == "momentum balance";
    }
    cg.kernel = upscale::cg::kernel_from_name(prm.get("kernel")).value_or(upscale::cg::KernelKind::gaussian);
    cg.width = prm.get_double("width");
    cg.at_quadrature_points = prm.get("evaluation points") == "quadrature points";
    cg.by_differences = prm.get("time derivative") == "differences";
    cg.sampling_interval = prm.get_double("sampling interval");
    cg.reference_time = prm.get_double("reference time");
  }
  prm.leave_subsection();

  prm.enter_subsection("Continuum");
  {
    ContinuumOptions& c = in.study.continuum;
    c.youngs_modulus = prm.get_double("youngs modulus");
    c.poisson_ratio = prm.get_double("poisson ratio");
    c.material_file = prm.get("material file");
    const std::string from = prm.get("material from");
    c.material_from = from == "calibration" ? ContinuumOptions::MaterialSource::calibration
                      : from == "entries"   ? ContinuumOptions::MaterialSource::entries
                                            : ContinuumOptions::MaterialSource::automatic;
    c.refinements = static_cast<unsigned>(prm.get_integer("refinements"));
    c.degree = static_cast<unsigned>(prm.get_integer("degree"));
    c.variants.clear();
    for (const std::string& name : dealii::Utilities::split_string_list(prm.get("variants"), ',')) {
      const ContinuumVariant v =
          name == "drucker prager" ? ContinuumVariant::drucker_prager : ContinuumVariant::elastic_friction;
      if (std::find(c.variants.begin(), c.variants.end(), v) == c.variants.end()) c.variants.push_back(v);
    }
    c.wall_friction_entry = prm.get("wall friction");
    c.floor_friction_entry = prm.get("floor friction");
    c.friction_angle_deg = prm.get_double("friction angle");
    c.dilatancy_angle_deg = prm.get_double("dilatancy angle");
    c.cohesion = prm.get_double("cohesion");
    const std::string matching = prm.get("cone matching");
    c.cone_matching = matching == "inner cone"     ? fem::ConeMatching::inner
                      : matching == "plane strain" ? fem::ConeMatching::plane_strain
                                                   : fem::ConeMatching::outer;
    c.load_steps = static_cast<unsigned>(prm.get_integer("load steps"));
    c.staged_construction = prm.get_bool("staged construction");
  }
  prm.leave_subsection();
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
    if (other != value && !may_change(key)) out.push_back(key + ": '" + value + "' -> '" + other + "'");
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

SceneInput read_scene_file(const std::string& filename, Command command) {
  SceneInput in = parse_scene_text(read_scene_bytes(filename), filename);
  in.command = command;
  in.scene_folder = std::filesystem::path(filename).parent_path().string();
  apply_material_file(in, filename);
  validate_scene(in);
  return in;
}

SceneInput default_scene(Command command) {
  ParameterHandler prm;
  declare(prm);
  SceneInput in = extract(prm, "built-in default scene");
  in.command = command;
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
         "declares them (`coupling/parameter_schema.cc`); do not edit by hand.\n\n"
      << "A scene file is a deal.II parameter file: `subsection <Name>`, `set <entry> = <value>`, "
         "`end`; `#` starts a comment. Unknown entries, values out of range and malformed lines "
         "stop the run before anything is written, with the file and line.\n";
  for (const std::string& section : sections()) {
    out << "\n## " << section
        << "\n\n| entry | default | allowed | unit | meaning |\n|---|---|---|---|---|\n";
    for (const ParameterSpec& p : parameter_schema()) {
      if (p.section != section) continue;
      std::string allowed;
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
      out << "| `" << p.name << "` | `" << p.default_value << "` | " << r.str() << " | " << p.unit << " | "
          << p.doc << " |\n";
    }
  }
}

}  // namespace upgrain::coupling
