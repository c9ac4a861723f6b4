// The Effects section: which physical effects the engine simulates, each auto (derived from the
// scene, dem/scene/effect_choice.h), true or false; switching off one a parameter calls for is refused.
#include "coupling/input/scene_sections.h"
#include "coupling/scene_input.h"
#include "dem/scene/effect_choice.h"

namespace upgrain::coupling::input {

Section effects_section() {
  return {
      "Effects",
      {choice("gravity", at(&SceneInput::effect_switches, &dem::EffectSwitches::gravity),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Gravity along -z. auto: on when 'gravity acceleration' > 0."),
       real("gravity acceleration", at(&SceneInput::scene, &dem::SceneConfig::gravity), 0.0, 1e3, "m/s^2",
            "Magnitude of gravity."),
       choice("tangential friction", at(&SceneInput::effect_switches, &dem::EffectSwitches::friction),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Mindlin tangential spring with Coulomb friction between particles. auto: on when "
              "Contact/friction coefficient > 0; off means frictionless contacts and no tangential "
              "history."),
       choice("damping", at(&SceneInput::effect_switches, &dem::EffectSwitches::damping),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Normal viscous damping c_n = 2 zeta sqrt(m* k_n). auto: on when Contact/damping ratio > 0."),
       choice("wall friction", at(&SceneInput::effect_switches, &dem::EffectSwitches::wall_friction),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Mindlin tangential spring with Coulomb friction at walls. auto: on when a Container wall "
              "friction is > 0; off means frictionless walls and no wall history."),
       choice("rotation", at(&SceneInput::effect_switches, &dem::EffectSwitches::rotation),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Integrate the angular velocity from contact torques. auto: on when a torque can act "
              "(friction, wall friction, rolling resistance or ellipsoids). false holds every grain from "
              "turning."),
       choice("energy tracking", at(&SceneInput::effect_switches, &dem::EffectSwitches::energy_tracking),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Accumulate elastic energy and dissipation per contact for the energy balance. auto: on "
              "when Output/energy balance is true."),
       choice("rolling resistance",
              at(&SceneInput::effect_switches, &dem::EffectSwitches::rolling_resistance),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Rolling resistance at every contact: elastic-plastic spring-dashpot (Iwashita and Oda "
              "1998; Ai et al. 2011, model C), |M_r| <= mu_r R* F_n. Not part of the paper's law: auto is"
              " off. Needs rotation."),
       choice("twisting resistance",
              at(&SceneInput::effect_switches, &dem::EffectSwitches::twisting_resistance),
              {{"auto", dem::EffectSwitch::automatic},
               {"true", dem::EffectSwitch::on},
               {"false", dem::EffectSwitch::off}},
              "Twisting resistance at every contact: Hertz–Mindlin torsion of the contact circle (Lubkin "
              "1951; Johnson 1985, 7.4), stiffness 16/3 G a^3, full slip at 3 pi/16 mu a F_n, with the "
              "rolling dashpot's damping ratio. Stops grains spinning about a contact normal (needles, "
              "discs). Not part of the paper's law: auto is off. Needs rolling resistance.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
