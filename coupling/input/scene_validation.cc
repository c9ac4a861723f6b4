#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include "coupling/input/scene_input.h"
#include "coupling/input/scene_limits.h"
#include "coupling/input/scene_sections.h"
#include "dem/core/error.h"
#include "dem/io/packing_file.h"
#include "dem/scene/fill.h"
#include "dem/scene/grain_shape.h"
#include "dem/scene/insertion.h"
#include "dem/time_step.h"

namespace upgrain::coupling {

namespace {

// Stress/box: "auto", or six reals x0, y0, z0, x1, y1, z1 with x1 > x0 etc.
void apply_stress_box(SceneInput& in, const std::string& where) {
  dem::io::GridStressOptions& gs = in.output.grid_stress;
  std::string text = in.stress_box;
  text.erase(0, text.find_first_not_of(" \t"));
  text.erase(text.find_last_not_of(" \t") + 1);
  if (text == "auto" || text.empty()) {
    gs.fixed_box = false;
    return;
  }
  std::vector<double> v;
  std::istringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    std::istringstream one(item);
    double x = 0.0;
    std::string rest;
    if (!(one >> x) || (one >> rest) || !std::isfinite(x))
      throw Error(where + "Stress/box = '" + in.stress_box + "': '" + item +
                  "' is not a number; give 'auto' or 'x0, y0, z0, x1, y1, z1' in m");
    v.push_back(x);
  }
  if (v.size() != 6)
    throw Error(where + "Stress/box = '" + in.stress_box + "' has " + std::to_string(v.size()) +
                " numbers; give 'auto' or six: 'x0, y0, z0, x1, y1, z1' in m");
  gs.fixed_box = true;
  gs.lo = dem::Vec3(v[0], v[1], v[2]);
  gs.hi = dem::Vec3(v[3], v[4], v[5]);
  for (int d = 0; d < 3; ++d)
    if (!(gs.hi[d] > gs.lo[d]))
      throw Error(where + "Stress/box = '" + in.stress_box + "' is empty along " + "xyz"[d] +
                  ": the upper bound must exceed the lower");
}

// Container/periodic axes against the rest of the scene (docs/periodic.md): a periodic axis
// longer than twice the interaction range (the minimum image is then the only image in range),
// no wall that would sit on a periodic face, no gravity along a periodic z.
void validate_periodic(const SceneInput& in, const std::string& where) {
  const dem::SceneConfig& s = in.scene;
  const std::array<bool, 3>& periodic = s.container.periodic;
  const double d_max = 2.0 * s.particles.largest_radius();
  const double range = d_max + s.neighbor_skin * d_max;
  const char* entry[3] = {"Container/length x", "Container/length y", "Container/height"};
  const double length[3] = {s.container.lx, s.container.ly, s.container.height};
  for (int d = 0; d < 3; ++d) {
    if (!periodic[d] || length[d] > 2.0 * range) continue;
    std::ostringstream m;
    m << where << entry[d] << " = " << length[d] << " m: along the periodic axis "
      << "xyz"[d] << " (Container/periodic axes) the cell must be longer than twice the interaction range, "
      << 2.0 * range << " m (twice the largest grain diameter, " << d_max
      << " m, plus the Verlet skin, Simulation/neighbor skin), so that a grain meets one image of another";
    throw Error(m.str());
  }
  if (periodic[0] && s.container.has_gate())
    throw Error(where +
                "Container/gate x with Container/periodic axes = x: a periodic x has no walls to hold a "
                "gate between; set 'gate x = 0' or take x out of 'periodic axes'");
  if ((periodic[0] || periodic[1]) && s.container.opens_side_walls())
    throw Error(where +
                "Container/side walls open time with a periodic x or y (Container/periodic axes): "
                "a periodic axis has no side walls to open");
  if (periodic[2] && s.effects.gravity)
    throw Error(where +
                "Container/periodic axes = z with gravity on: grains would fall through the cell for "
                "ever; keep z walled (a floor) or set Effects/gravity = false");
}

// The Cell section against the container (docs/periodic.md, "A cell that deforms"): a deforming
// axis is periodic; a prescribed rate keeps the cell, by Simulation/end time, longer than twice
// the interaction range (shorter, and it would meet a grain's second image, then invert) and
// within its grid's growth; checkpoints of a deforming cell are not available yet.
void validate_cell(const SceneInput& in, const std::string& where) {
  const dem::SceneConfig& s = in.scene;
  if (!s.cell.any()) return;
  const double d_max = 2.0 * s.particles.largest_radius();
  const double range = d_max + s.neighbor_skin * d_max;
  const double length[3] = {s.container.lx, s.container.ly, s.container.height};
  if (const dem::CellShearControl& c = s.cell.shear; c.any()) {
    const std::string name = std::string(1, "xyz"[c.shear()]) + "xyz"[c.gradient()];
    for (int d : c.component)
      if (!s.container.periodic[d])
        throw Error(where + "Cell/shear component = " + name + " shears the cell across " + "xyz"[d] +
                    ", which is not periodic: add it to Container/periodic axes");
  }
  for (int d = 0; d < 3; ++d) {
    const dem::CellAxisControl& c = s.cell.axis[d];
    if (c.mode == dem::CellAxisMode::fixed) continue;
    const std::string a(1, "xyz"[d]);
    if (!s.container.periodic[d])
      throw Error(where + "Cell/mode " + a + " deforms the cell along " + a +
                  ", which is not periodic: add " + a + " to Container/periodic axes or set 'mode " + a +
                  " = fixed'");
    if (c.mode != dem::CellAxisMode::rate) continue;
    // h' = L h: the length at the end is l exp(L t) (the steps' product (1 + dt L)^n, which
    // inverts at once when dt L <= -1).
    const double end = length[d] * std::exp(c.rate * s.end_time);
    std::ostringstream m;
    m << where << "Cell/strain rate " << a << " = " << c.rate << " 1/s: ";
    if (c.rate * s.time_step <= -1.0)
      m << "one time step (" << s.time_step << " s) would invert the cell along " << a;
    else if (end <= 2.0 * range)
      m << "by Simulation/end time = " << s.end_time << " s the cell's length along " << a
        << " would shrink from " << length[d] << " m to " << end
        << " m, not longer than twice the interaction range, " << 2.0 * range
        << " m: the cell would collapse onto its grains (and invert); lower the rate or the end time";
    else if (end > s.cell.max_growth * length[d])
      m << "by Simulation/end time = " << s.end_time << " s the cell's length along " << a
        << " would grow from " << length[d] << " m to " << end
        << " m, past Cell/max growth = " << s.cell.max_growth << " times its first length";
    else
      continue;
    throw Error(m.str());
  }
}

// Container/collapse against the entries of the other scene: the gate belongs to the
// constrained collapse (a 'gate x' > 0 alone also selects it, as before 'collapse'
// existed), 'side walls open time' to the unconstrained one, and no entry of the other
// scene may be set.
void validate_collapse(const SceneInput& in, const std::string& where) {
  const dem::BoxContainer& c = in.scene.container;
  const std::string& mode = in.collapse;
  if (mode != "none" && mode != "constrained" && mode != "unconstrained")
    throw Error(where + "Container/collapse = '" + mode + "': give none, constrained or unconstrained");
  std::ostringstream m;
  m << where;
  if (mode == "constrained" && !c.has_gate()) {
    m << "Container/collapse = constrained needs a gate: set Container/gate x (> 0, inside the box) and "
         "'gate open time'";
    throw Error(m.str());
  }
  if (mode != "unconstrained" && c.opens_side_walls()) {
    m << "Container/side walls open time = " << c.side_walls_open_time
      << " s is for the unconstrained collapse, but Container/collapse = " << mode
      << "; set 'collapse = unconstrained' or remove the entry";
    throw Error(m.str());
  }
  if (mode != "unconstrained") return;
  if (c.has_gate()) {
    m << "Container/gate x = " << c.gate_x
      << " m is for the constrained collapse, but Container/collapse = unconstrained (all side walls "
         "open at 'side walls open time'); set 'gate x = 0' or 'collapse = constrained'";
    throw Error(m.str());
  }
  if (!(c.side_walls_open_time > 0.0) || c.side_walls_open_time >= in.scene.end_time) {
    m << "Container/side walls open time = " << c.side_walls_open_time
      << " s must lie in (0, Simulation/end time = " << in.scene.end_time
      << " s) for Container/collapse = unconstrained";
    throw Error(m.str());
  }
  if (compares_with_continuum(in))
    throw Error(where +
                "Container/collapse = unconstrained removes the side walls that the continuum column "
                "needs; set 'Study/compare with continuum = false'");
}

// The shapes of a packing's grains that set the safe time step (dem/time_step.cc): the thinnest,
// the flattest and the lightest for its size (dem::ShapeScales). Empty when every grain is a
// sphere.
std::vector<dem::GrainShape> limiting_shapes(const dem::ParticleStore& p) {
  std::vector<dem::GrainShape> out;
  if (!p.has_shapes()) return out;
  std::optional<dem::GrainShape> thinnest, flattest, lightest;
  auto keep = [](std::optional<dem::GrainShape>& held, const dem::GrainShape& g, auto scale, bool larger) {
    if (!held || (larger ? scale(g) > scale(*held) : scale(g) < scale(*held))) held = g;
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.oriented(i)) continue;
    const dem::GrainShape g = dem::grain_shape_of(p, i);
    keep(
        thinnest, g, [](const dem::GrainShape& s) { return dem::scales(s).thinnest; }, false);
    keep(
        flattest, g, [](const dem::GrainShape& s) { return dem::scales(s).flattest; }, true);
    keep(
        lightest, g, [](const dem::GrainShape& s) { return dem::scales(s).volume; }, false);
  }
  for (const auto& g : {thinnest, flattest, lightest})
    if (g) out.push_back(*g);
  return out;
}

// Particles/initial packing: the grains read and checked against the container, and the
// Particles entries made to describe them (count, smallest radius, the limiting shapes), so
// that every later check (fit, time step, stiffness, memory) sees the grains of the file.
void load_initial_packing(SceneInput& in, const std::string& where) {
  dem::SceneConfig& s = in.scene;
  s.particles.packing.reset();
  in.packing_note.clear();
  if (in.initial_packing.empty()) return;
  std::filesystem::path path = in.initial_packing;
  if (path.is_relative() && !in.scene_folder.empty()) path = std::filesystem::path(in.scene_folder) / path;
  dem::io::Packing p;
  try {
    p = dem::io::read_packing(path, s.particles.material.density);
    dem::io::check_packing(p, s.container, path.string(), dem::io::kPackingOverlapLimit);
  } catch (const Error& e) {
    throw Error(where + "Particles/initial packing: " + e.what());
  }
  for (const std::string& note : p.notes) in.warnings.push_back(where + note);
  s.particles.count = static_cast<long>(p.grains.size());
  s.particles.radius = p.grains.min_radius();
  s.particles.gradation.clear();
  s.particles.shapes = limiting_shapes(p.grains);
  in.packing_note = "initial packing: " + path.string() + " (" + p.format + ", " +
                    std::to_string(p.grains.size()) + " grains)";
  s.particles.packing = std::make_shared<const dem::ParticleStore>(std::move(p.grains));
}

}  // namespace

bool compares_with_continuum(const SceneInput& in) {
  return in.use.scene_study && in.study.compare_with_continuum;
}

bool uses_continuum_material(const SceneInput& in) {
  return compares_with_continuum(in) || in.use.continuum_material;
}

bool calibrates(const SceneInput& in) {
  return in.use.calibrates || (compares_with_continuum(in) && in.study.continuum.calibrate_in_study);
}

void validate_scene(SceneInput& in) {
  const dem::SceneConfig& s = in.scene;
  const std::string where = in.source + ": ";
  in.warnings.clear();
  load_initial_packing(in, where);
  // The effect set first: the time-step estimate below depends on it (gravity).
  try {
    dem::ChosenEffects chosen = dem::choose_effects(s, in.effect_switches, {in.output.energy_balance});
    in.scene.effects = chosen.set;
    in.output.effect_choices = std::move(chosen.choices);
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
  apply_stress_box(in, where);
  // Each section's own checks (its file in input/sections/), then those across sections.
  input::check_sections(in, where);
  const double r_max = s.particles.largest_radius();
  if (2.0 * r_max >= std::min(s.container.lx, s.container.ly)) {
    std::ostringstream m;
    m << where << "the largest grain (diameter " << 2 * r_max << " m, Particles/radius or gradation) "
      << "does not fit between the walls (Container/length x = " << s.container.lx
      << " m, length y = " << s.container.ly << " m)";
    throw Error(m.str());
  }
  validate_collapse(in, where);
  validate_periodic(in, where);
  validate_cell(in, where);
  if (s.container.has_gate()) {
    if (s.container.gate_x >= s.container.lx || 2.0 * r_max >= s.container.gate_x) {
      std::ostringstream m;
      m << where << "Container/gate x = " << s.container.gate_x << " m must lie between the largest grain's "
        << "diameter (" << 2 * r_max << " m) and Container/length x = " << s.container.lx << " m";
      throw Error(m.str());
    }
    if (!(s.container.gate_open_time > 0.0) || s.container.gate_open_time >= s.end_time) {
      std::ostringstream m;
      m << where << "Container/gate open time = " << s.container.gate_open_time
        << " s must lie in (0, Simulation/end time = " << s.end_time << " s)";
      throw Error(m.str());
    }
  }
  if (s.insertion.enabled() && !in.initial_packing.empty())
    throw Error(where +
                "Insertion/count > 0 with Particles/initial packing: a pour takes the scene's gradation and "
                "shapes, which a packing replaces; pour into a fill, or set 'Insertion/count = 0'");
  check_memory(in, where);
  check_gradation_sampling(in, where);
  try {
    dem::validate_insertion(s);  // after the memory check: it draws the pour's radii
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
  if (const dem::InletLoad load = dem::inlet_load(s); load.held > dem::kBatchFillLimit) {
    std::ostringstream m;
    m.precision(3);
    m << where << "Insertion: the batches that lie in the inlet together before their grains fall out of it "
      << "fill " << load.held << " of it (one batch " << load.batch
      << "): grains will wait and the pour will fall behind its rate; make the inlet taller, give a "
         "downward Insertion/velocity or a lower rate";
    in.warnings.push_back(m.str());
  }
  double fill_top = 0.0;
  try {
    fill_top = dem::plan_fill(s).top;
  } catch (const Error& e) {
    throw Error(where + e.what());
  }
  check_fill_height(in, fill_top, where);
  check_stiffness(in, where);
  check_stress_box(in, fill_top, where);
  check_output_intervals(in, where);
  const dem::TimeStepEstimate ts = dem::estimate_time_step(s);
  if (s.time_step > ts.safe_step && !s.time_step_rule.allow_unsafe) {
    std::ostringstream m;
    m.precision(4);
    m << where << "Simulation/time step = " << s.time_step << " s exceeds the safe step " << ts.safe_step
      << " s (" << ts.limiting << "-limited: ";
    if (ts.rayleigh_time > 0.0)
      m << s.time_step_rule.rayleigh_fraction << " x Rayleigh time " << ts.rayleigh_time << " s, ";
    m << s.time_step_rule.hertz_fraction << " x " << s.contact_law << " contact time " << ts.contact_time
      << " s";
    if (ts.hertz_time > 0.0) m << " at " << ts.impact_speed << " m/s";
    m << "); lower the time step or set 'allow unsafe time step = true'";
    throw Error(m.str());
  }
  if (s.end_time < s.time_step) {
    std::ostringstream m;
    m << where << "Simulation/end time = " << s.end_time << " s is shorter than one time step";
    throw Error(m.str());
  }
  if (const double steps = s.end_time / s.time_step; steps > in.maximum_steps) {
    // A step in the wrong unit (1e-12 s for 1e-6 s) asks for a run that would never end.
    std::ostringstream m;
    m.precision(3);
    m << where << "Simulation/end time = " << s.end_time << " s at Simulation/time step = " << s.time_step
      << " s is " << steps << " steps, more than Simulation/maximum steps = " << in.maximum_steps
      << "; check the two entries' units, or raise Simulation/maximum steps";
    throw Error(m.str());
  }
  // The scene's lid; the calibration study deposits its bed without it (docs/calibration.md).
  if (in.use.scene_lid) {
    try {
      validate_lid(in.control.lid, s);
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
    if (in.control.lid.enabled() && in.control.lid.friction > 0.0 && !in.scene.effects.wall_friction)
      throw Error(where +
                  "Lid/friction > 0, but Effects/wall friction is off: the lid would be frictionless; set "
                  "'Lid/friction = 0' or turn wall friction on");
  }
  if (const upscale::GridStrainOutputOptions& st = in.output.grid_strain; st.enabled) {
    if (!in.output.grid_stress.enabled())
      throw Error(where +
                  "Strain/enabled = true needs the stress grid, but Stress/formulas is empty; name at least "
                  "one formula there (strain is evaluated with the grid stress, on its grid), or set "
                  "'Strain/enabled = false'");
    if (const auto& written = in.output.grid_stress.formulas;
        std::find(written.begin(), written.end(), st.rate_formula) == written.end())
      throw Error(where + "Strain/rate formula = '" + std::string(dem::name_of(st.rate_formula)) +
                  "' is not in Stress/formulas: the stress rates need its grid stress; add it there or "
                  "choose one of the formulas written");
    if (st.reference_time > s.end_time) {
      std::ostringstream m;
      m << where << "Strain/reference time = " << st.reference_time
        << " s is after Simulation/end time = " << s.end_time << " s: no strain would be written";
      throw Error(m.str());
    }
  }
  // What the run keeps for the coarse-grained fields: nothing, unless the study captures them.
  in.output.coarse_graining = CoarseGrainingCapture{};
  // Last, once the scene itself is known sound: the study's own checks. The output folder is not
  // part of the scene: the driver checks it for a run, after the command line has chosen it
  // (check_output_folder).
  if (in.use.check != nullptr) in.use.check(in, where);
}

}  // namespace upgrain::coupling
