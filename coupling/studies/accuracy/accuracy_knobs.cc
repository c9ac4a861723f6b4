#include "coupling/studies/accuracy/accuracy_knobs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dem/core/error.h"
#include "dem/time_step.h"

namespace upgrain::coupling {

namespace {

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

bool has_shapes(const SceneInput& in) { return dem::has_shapes(in.scene.particles.shapes); }

KnobSetting setting(std::string knob, std::string label, double value, bool is_default) {
  KnobSetting k;
  k.knob = std::move(knob);
  k.label = std::move(label);
  k.value = value;
  k.is_default = is_default;
  k.apply = [](SceneInput&) {};
  return k;
}

// The values to try with the scene's own setting among them (so that every plot marks it),
// in ascending order.
std::vector<double> with_scene_setting(std::vector<double> values, double own) {
  if (std::find(values.begin(), values.end(), own) == values.end()) values.push_back(own);
  std::sort(values.begin(), values.end());
  return values;
}

// The time step at `fraction` of the safe step of `scene`.
double step_at(const dem::SceneConfig& scene, double fraction) {
  return fraction * dem::estimate_time_step(scene).safe_step;
}

}  // namespace

const std::vector<std::string>& knob_names() {
  static const std::vector<std::string> names = {"time step",
                                                 "youngs modulus",
                                                 "skin",
                                                 "summation",
                                                 "ranks",
                                                 "shape",
                                                 "rotation",
                                                 "rolling resistance",
                                                 "solver tolerance",
                                                 "solver iterations",
                                                 "relaxation tolerance",
                                                 "grid",
                                                 "fem",
                                                 "outputs"};
  return names;
}

std::vector<KnobSetting> knob_settings(const SceneInput& base, const AccuracyOptions& o, int ranks,
                                       std::vector<std::string>& skipped) {
  for (const std::string& k : o.knobs)
    if (std::find(knob_names().begin(), knob_names().end(), k) == knob_names().end())
      throw Error("Accuracy/knobs: unknown knob '" + k + "'");
  auto chosen = [&](const char* k) { return std::find(o.knobs.begin(), o.knobs.end(), k) != o.knobs.end(); };
  auto nonempty = [](const auto& list, const char* entry) {
    if (list.empty()) throw Error(std::string("Accuracy/") + entry + ": no values to try");
  };
  std::vector<KnobSetting> out;
  const dem::SceneConfig& s = base.scene;
  const double safe = dem::estimate_time_step(s).safe_step;
  const double own_fraction = s.time_step / safe;

  if (chosen("time step")) {
    nonempty(o.time_step_fractions, "time step fractions");
    for (double x : o.time_step_fractions)
      if (!(x > 0.0 && x <= 2.0))
        throw Error("Accuracy/time step fractions: " + number(x) + " is not in (0, 2]");
    for (double x : with_scene_setting(o.time_step_fractions, own_fraction)) {
      KnobSetting k = setting("time step", number(x) + " of the safe step", x, x == own_fraction);
      k.apply = [x](SceneInput& in) {
        in.scene.time_step = step_at(in.scene, x);
        in.scene.time_step_rule.allow_unsafe = x > 1.0;
      };
      out.push_back(std::move(k));
    }
  }
  if (chosen("youngs modulus")) {
    nonempty(o.modulus_factors, "modulus factors");
    for (double x : o.modulus_factors) {
      if (!(x > 0.0 && x <= 1.0)) throw Error("Accuracy/modulus factors: " + number(x) + " is not in (0, 1]");
      KnobSetting k = setting("youngs modulus", "E x " + number(x), x, x == 1.0);
      // The softer grains with the step they allow, at the scene's own fraction of it: the
      // shortcut as users take it.
      k.apply = [x, own_fraction](SceneInput& in) {
        in.scene.particles.material.youngs_modulus *= x;
        in.scene.time_step = step_at(in.scene, own_fraction);
      };
      out.push_back(std::move(k));
    }
  }
  if (chosen("skin")) {
    nonempty(o.skins, "skins");
    for (double x : o.skins) {
      if (!(x > 0.0 && x <= 2.0)) throw Error("Accuracy/skins: " + number(x) + " is not in (0, 2]");
      KnobSetting k = setting("skin", number(x) + " diameters", x, x == s.neighbor_skin);
      k.apply = [x](SceneInput& in) { in.scene.neighbor_skin = x; };
      out.push_back(std::move(k));
    }
  }
  if (chosen("summation")) {
    const bool fast = base.parallel.summation == dem::Summation::fast;
    for (const bool f : {false, true}) {
      KnobSetting k = setting("summation", f ? "fast" : "deterministic", f ? 1.0 : 0.0, f == fast);
      k.apply = [f](SceneInput& in) {
        in.parallel.summation = f ? dem::Summation::fast : dem::Summation::deterministic;
      };
      out.push_back(std::move(k));
    }
  }
  if (chosen("ranks")) {
    if (ranks < 2) {
      skipped.push_back("ranks: the study runs on one rank (start it under mpirun to compare rank counts)");
    } else {
      KnobSetting one = setting("ranks", "1 rank", 1.0, false);
      one.run = SettingRun::dem_one_rank;
      one.apply = [](SceneInput&) {};
      out.push_back(std::move(one));
      KnobSetting all = setting("ranks", std::to_string(ranks) + " ranks", static_cast<double>(ranks), true);
      all.apply = [](SceneInput&) {};
      out.push_back(std::move(all));
    }
  }
  if (chosen("shape")) {
    if (!has_shapes(base)) {
      skipped.push_back("shape: the scene has spheres only");
    } else {
      // Spheres of the mix's mean grain volume: the size scaled by the number-weighted mean of
      // the cube root of each shape's volume over its size's sphere (an ellipsoid's b/a c/a).
      double weight = 0.0, factor = 0.0;
      for (const dem::GrainShape& g : s.particles.shapes) {
        weight += g.number_fraction;
        factor += g.number_fraction * std::cbrt(dem::scales(g).volume);
      }
      factor /= weight;
      KnobSetting own = setting("shape", "the scene's shapes", 1.0, true);
      own.apply = [](SceneInput&) {};
      out.push_back(std::move(own));
      KnobSetting spheres = setting("shape", "volume-equivalent spheres", 0.0, false);
      spheres.apply = [factor](SceneInput& in) {
        in.scene.particles.shapes.clear();
        in.scene.particles.radius *= factor;
        for (dem::GradationPoint& p : in.scene.particles.gradation) p.radius *= factor;
      };
      out.push_back(std::move(spheres));
    }
  }
  if (chosen("rotation")) {
    KnobSetting on = setting("rotation", "rotation integrated", 1.0, true);
    on.apply = [](SceneInput&) {};
    out.push_back(std::move(on));
    KnobSetting off = setting("rotation", "rotation held", 0.0, false);
    off.apply = [](SceneInput& in) { in.effect_switches.rotation = dem::EffectSwitch::off; };
    out.push_back(std::move(off));
  }
  if (chosen("rolling resistance")) {
    KnobSetting off = setting("rolling resistance", "none", 0.0, !s.effects.rolling_resistance);
    off.apply = [](SceneInput& in) {
      in.effect_switches.rolling_resistance = dem::EffectSwitch::off;
      in.effect_switches.twisting_resistance = dem::EffectSwitch::off;  // a part of it
    };
    out.push_back(std::move(off));
    KnobSetting on = setting("rolling resistance", "mu_r = " + number(s.rolling_friction), 1.0,
                             s.effects.rolling_resistance);
    on.apply = [](SceneInput& in) { in.effect_switches.rolling_resistance = dem::EffectSwitch::on; };
    out.push_back(std::move(on));
  }
  // The ellipsoid contact solver's stopping rules (dem/contact/contact_solver_settings.h).
  const dem::ContactSolverSettings& solver = s.contact_solver;
  if (chosen("solver tolerance")) {
    if (!has_shapes(base)) {
      skipped.push_back("solver tolerance: the scene has spheres only (no contact solver)");
    } else {
      nonempty(o.solver_tolerances, "solver tolerances");
      for (double x : o.solver_tolerances)
        if (!(x >= 16.0 && x <= 1e12))
          throw Error("Accuracy/solver tolerances: " + number(x) + " is not in [16, 1e12]");
      for (double x : with_scene_setting(o.solver_tolerances, solver.gradient_tolerance)) {
        KnobSetting k =
            setting("solver tolerance", number(x) + " eps x size", x, x == solver.gradient_tolerance);
        k.apply = [x](SceneInput& in) { in.scene.contact_solver.gradient_tolerance = x; };
        out.push_back(std::move(k));
      }
    }
  }
  if (chosen("solver iterations")) {
    if (!has_shapes(base)) {
      skipped.push_back("solver iterations: the scene has spheres only (no contact solver)");
    } else {
      nonempty(o.solver_iteration_caps, "solver iteration caps");
      for (double x : o.solver_iteration_caps)
        if (!(x >= 1.0 && x <= 1000.0 && x == std::floor(x)))
          throw Error("Accuracy/solver iteration caps: " + number(x) + " is not a whole number in 1..1000");
      // Most steps first: from the exact solve down.
      std::vector<double> values = with_scene_setting(o.solver_iteration_caps, solver.max_iterations);
      std::reverse(values.begin(), values.end());
      for (double x : values) {
        const int cap = static_cast<int>(x);
        KnobSetting k = setting("solver iterations", std::to_string(cap) + " Newton steps", x,
                                cap == solver.max_iterations);
        k.apply = [cap](SceneInput& in) { in.scene.contact_solver.max_iterations = cap; };
        out.push_back(std::move(k));
      }
    }
  }
  if (chosen("relaxation tolerance")) {
    if (!base.control.relax_at_end) {
      skipped.push_back("relaxation tolerance: the scene does not relax at its end (Study/relax at end)");
    } else {
      nonempty(o.relaxation_tolerances, "relaxation tolerances");
      for (double x : o.relaxation_tolerances) {
        if (!(x > 0.0 && x < 1.0))
          throw Error("Accuracy/relaxation tolerances: " + number(x) + " is not in (0, 1)");
        KnobSetting k =
            setting("relaxation tolerance", number(x), x, x == base.control.relaxation.force_tolerance);
        k.apply = [x](SceneInput& in) { in.control.relaxation.force_tolerance = x; };
        out.push_back(std::move(k));
      }
    }
  }
  if (chosen("grid")) {
    if (!base.output.grid_stress.enabled()) {
      skipped.push_back("grid: the scene writes no grid stress (Stress/formulas)");
    } else {
      nonempty(o.grids, "grids");
      for (const std::array<int, 3>& g : o.grids) {
        for (int n : g)
          if (n < 1 || n > 100)
            throw Error("Accuracy/grids: " + std::to_string(n) + " cells is not in 1..100");
        const int* own = base.output.grid_stress.cells;
        KnobSetting k = setting(
            "grid", std::to_string(g[0]) + " x " + std::to_string(g[1]) + " x " + std::to_string(g[2]),
            static_cast<double>(g[0] * g[1] * g[2]), g[0] == own[0] && g[1] == own[1] && g[2] == own[2]);
        k.apply = [g](SceneInput& in) {
          for (int d = 0; d < 3; ++d) in.output.grid_stress.cells[d] = g[d];
        };
        out.push_back(std::move(k));
      }
    }
  }
  if (chosen("fem")) {
    nonempty(o.fem_degrees, "fem degrees");
    nonempty(o.fem_refinements, "fem refinements");
    for (unsigned d : o.fem_degrees)
      for (unsigned r : o.fem_refinements) {
        if (d < 1 || d > 4) throw Error("Accuracy/fem degrees: " + std::to_string(d) + " is not in 1..4");
        if (r > 5) throw Error("Accuracy/fem refinements: " + std::to_string(r) + " is above 5");
        std::string label = "Q";  // built in steps: GCC 12 warns falsely on a chain of + here
        label += std::to_string(d);
        label += ", ";
        label += std::to_string(r);
        label += " refinements";
        KnobSetting k = setting("fem", label, static_cast<double>(d * 10 + r),
                                d == base.study.continuum.degree && r == base.study.continuum.refinements);
        k.run = SettingRun::fem;
        k.fem_degree = d;
        k.fem_refinements = r;
        out.push_back(std::move(k));
      }
  }
  if (chosen("outputs")) {
    KnobSetting all = setting("outputs", "energy, stress and strain as the scene asks", 3.0, true);
    all.apply = [](SceneInput&) {};
    out.push_back(std::move(all));
    KnobSetting no_energy = setting("outputs", "no energy tracking", 2.0, false);
    no_energy.apply = [](SceneInput& in) { in.output.energy_balance = false; };
    out.push_back(std::move(no_energy));
    KnobSetting no_grid = setting("outputs", "no grid stress or strain", 1.0, false);
    no_grid.apply = [](SceneInput& in) {
      in.output.grid_stress.formulas.clear();
      in.output.grid_strain.enabled = false;
    };
    out.push_back(std::move(no_grid));
  }
  return out;
}

}  // namespace upgrain::coupling
