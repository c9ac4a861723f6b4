#include "dem/scene/effect_choice.h"
#include "dem/files/json_number.h"

#include <algorithm>
#include <sstream>

#include "dem/core/error.h"

namespace upgrain::dem {

namespace {

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// One entry: the explicit switch wins; `derived` and `why` are what the scene calls for.
// `needed`: the scene's parameters need the effect, so an explicit false is refused with
// `why` as the reason.
struct Entry {
  const char* name;
  EffectSwitch sw;
  bool derived;
  std::string why;
  bool needed;
};

EffectChoice decide(const Entry& e) {
  const std::string parameter = std::string("Effects/") + e.name;
  switch (e.sw) {
    case EffectSwitch::on:
      return {e.name, true, "set in the scene (" + parameter + " = true)"};
    case EffectSwitch::off:
      if (e.needed)
        throw Error(parameter + " = false contradicts the scene: " + e.why +
                    "; set the parameter that calls for it to zero, or " + parameter + " = auto");
      return {e.name, false, "set in the scene (" + parameter + " = false)"};
    case EffectSwitch::automatic:
      break;
  }
  return {e.name, e.derived, e.why};
}

}  // namespace

EffectSwitch parse_effect_switch(const std::string& text, const std::string& parameter) {
  if (text == "auto") return EffectSwitch::automatic;
  if (text == "true") return EffectSwitch::on;
  if (text == "false") return EffectSwitch::off;
  throw Error(parameter + " = '" + text + "': write auto, true or false");
}

ChosenEffects choose_effects(const SceneConfig& s, const EffectSwitches& sw, const EffectNeeds& needs) {
  ChosenEffects out;
  auto add = [&](const Entry& e) {
    out.choices.push_back(decide(e));
    return out.choices.back().on;
  };
  EffectSet& set = out.set;

  const bool g = s.gravity > 0.0;
  set.gravity = add({"gravity", sw.gravity, g,
                     g ? "Effects/gravity acceleration = " + number(s.gravity) + " m/s^2"
                       : "Effects/gravity acceleration = 0",
                     g});

  const bool mu = s.friction > 0.0;
  set.friction = add({"tangential friction", sw.friction, mu,
                      mu ? "Contact/friction coefficient = " + number(s.friction)
                         : "Contact/friction coefficient = 0: no tangential spring, no history",
                      mu});

  const bool zeta = s.damping_ratio > 0.0;
  set.damping = add(
      {"damping", sw.damping, zeta,
       zeta ? "Contact/damping ratio = " + number(s.damping_ratio) : "Contact/damping ratio = 0: no dashpot",
       zeta});

  const double* wf = s.container.friction;
  const double wall_mu = *std::max_element(wf, wf + 5);
  const bool walls = wall_mu > 0.0;
  set.wall_friction =
      add({"wall friction", sw.wall_friction, walls,
           walls ? "a container wall has friction (largest coefficient " + number(wall_mu) + ")"
                 : "every container wall is frictionless: no wall history",
           walls});

  // Rolling resistance is not part of Yan and Regueiro's law (docs/stress.md): only on when asked for.
  const bool rolling_on = sw.rolling_resistance == EffectSwitch::on;
  const bool shapes = has_shapes(s.particles.shapes);
  const bool torques = set.friction || set.wall_friction || rolling_on || shapes;
  std::string why_rotation;
  if (shapes)
    why_rotation = shape_nouns(s.particles.shapes) + " turn under normal forces";
  else if (torques)
    why_rotation = "tangential forces or rolling resistance turn the spheres";
  else
    why_rotation = "frictionless spheres: no torque, no rotation work";
  // Switching rotation off is a modelling choice (grains held from turning), not a
  // contradiction, so it is never refused.
  set.rotation = add({"rotation", sw.rotation, torques, why_rotation, false});

  set.energy_tracking = add(
      {"energy tracking", sw.energy_tracking, needs.energy_balance,
       needs.energy_balance ? "Output/energy balance = true"
                            : "Output/energy balance = false: no elastic energy or dissipation per contact",
       needs.energy_balance});

  if (rolling_on && !set.rotation)
    throw Error("Effects/rolling resistance needs Effects/rotation = true (it acts on the spins)");
  set.rolling_resistance = add(
      {"rolling resistance", sw.rolling_resistance, false,
       "not part of Yan and Regueiro's law: on only when set (Effects/rolling resistance = true)", false});
  if (sw.twisting_resistance == EffectSwitch::on && !set.rolling_resistance)
    throw Error(
        "Effects/twisting resistance needs Effects/rolling resistance = true (the twisting spring is a part "
        "of the rolling resistance's springs)");
  set.twisting_resistance = add(
      {"twisting resistance", sw.twisting_resistance, false,
       "not part of Yan and Regueiro's law: on only when set (Effects/twisting resistance = true)", false});
  return out;
}

std::vector<EffectChoice> describe_effects(const EffectSet& e) {
  const std::string given = "given by the program that built the scene";
  return {{"gravity", e.gravity, given},
          {"tangential friction", e.friction, given},
          {"damping", e.damping, given},
          {"wall friction", e.wall_friction, given},
          {"rotation", e.rotation, given},
          {"energy tracking", e.energy_tracking, given},
          {"rolling resistance", e.rolling_resistance, given},
          {"twisting resistance", e.twisting_resistance, given}};
}

std::string effects_json(const std::vector<EffectChoice>& choices) {
  std::string j = "{";
  for (std::size_t k = 0; k < choices.size(); ++k) {
    const EffectChoice& c = choices[k];
    if (k > 0) j += ", ";
    j += io::json_string(c.entry) + ": {\"on\": " + (c.on ? "true" : "false") +
         ", \"reason\": " + io::json_string(c.reason) + "}";
  }
  return j + "}";
}

}  // namespace upgrain::dem
