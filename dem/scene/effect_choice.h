#pragma once
// Which physical effects a run simulates, derived from the scene's own parameters: a
// friction coefficient of 0 needs no tangential spring, a damping ratio of 0 no dashpot,
// spheres without tangential forces no rotation work. Each `Effects` entry of a scene file
// is `auto` (derived), `true` or `false`; an explicit setting wins, but switching off an
// effect the scene's parameters call for is refused instead of ignored. The choice and its
// reason per entry are printed at the start of a run and recorded in summary.json
// (docs/contact-law.md, "Effects from the scene").
#include <string>
#include <vector>

#include "dem/scene/scene_config.h"

namespace upgrain::dem {

enum class EffectSwitch { automatic, on, off };

// `auto`, `true` or `false` (as in a scene file); throws upgrain::Error naming `parameter`.
EffectSwitch parse_effect_switch(const std::string& text, const std::string& parameter);

// The `Effects` section as written.
struct EffectSwitches {
  EffectSwitch gravity = EffectSwitch::automatic;
  EffectSwitch friction = EffectSwitch::automatic;
  EffectSwitch damping = EffectSwitch::automatic;
  EffectSwitch wall_friction = EffectSwitch::automatic;
  EffectSwitch rotation = EffectSwitch::automatic;
  EffectSwitch energy_tracking = EffectSwitch::automatic;
  EffectSwitch rolling_resistance = EffectSwitch::automatic;
  EffectSwitch twisting_resistance = EffectSwitch::automatic;
};

// What the run's output asks of the engine.
struct EffectNeeds {
  bool energy_balance = true;  // elastic energy and dissipation in the time series and summary
};

// One entry of the effect set, as printed and recorded.
struct EffectChoice {
  std::string entry;   // the Effects parameter, e.g. "tangential friction"
  bool on = false;     // simulated
  std::string reason;  // why, in terms of the scene's parameters
};

struct ChosenEffects {
  EffectSet set;
  std::vector<EffectChoice> choices;  // in the order of the Effects section
};

// The effect set of `scene` (its friction, damping, gravity, container and shapes; its
// own `effects` member is not read). Throws upgrain::Error when an explicit `false`
// contradicts a parameter that needs the effect, or rolling resistance lacks rotation.
ChosenEffects choose_effects(const SceneConfig& scene, const EffectSwitches& switches,
                             const EffectNeeds& needs);

// A set given directly (by a program, not derived from a scene file), as choices.
std::vector<EffectChoice> describe_effects(const EffectSet& set);

// The choices as a JSON object {"entry": {"on": true, "reason": "..."}, ...}.
std::string effects_json(const std::vector<EffectChoice>& choices);

}  // namespace upgrain::dem
