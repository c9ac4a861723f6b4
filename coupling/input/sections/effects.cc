// The Effects section: which physical effects the engine simulates, each auto (derived from the
// scene, dem/scene/effect_choice.h), true or false; switching off one a parameter calls for is refused.
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"
#include "dem/scene/effect_choice.h"

namespace upgrain::coupling::input {

namespace {

// An effect's switch: auto, true or false.
Entry effect(std::string name, dem::EffectSwitch dem::EffectSwitches::*member, std::string doc) {
  return choice(std::move(name), at(&SceneInput::effect_switches, member),
                {{"auto", dem::EffectSwitch::automatic},
                 {"true", dem::EffectSwitch::on},
                 {"false", dem::EffectSwitch::off}},
                std::move(doc));
}

}  // namespace

Section effects_section() {
  return {
      "Effects",
      {effect("gravity", &dem::EffectSwitches::gravity,
              "Gravity along -z. auto: on when 'gravity acceleration' > 0."),
       real("gravity acceleration", at(&SceneInput::scene, &dem::SceneConfig::gravity), 0.0, 1e3, "m/s^2",
            "Magnitude of gravity."),
       effect("tangential friction", &dem::EffectSwitches::friction,
              "Mindlin tangential spring with Coulomb friction between particles. auto: on when "
              "Contact/friction coefficient > 0; off means frictionless contacts and no tangential "
              "history."),
       effect("damping", &dem::EffectSwitches::damping,
              "Normal viscous damping c_n = 2 zeta sqrt(m* k_n). auto: on when Contact/damping ratio > 0."),
       effect("wall friction", &dem::EffectSwitches::wall_friction,
              "Mindlin tangential spring with Coulomb friction at walls. auto: on when a Container wall "
              "friction is > 0; off means frictionless walls and no wall history."),
       effect("rotation", &dem::EffectSwitches::rotation,
              "Integrate the angular velocity from contact torques. auto: on when a torque can act "
              "(friction, wall friction, rolling resistance or ellipsoids). false holds every grain from "
              "turning."),
       effect("energy tracking", &dem::EffectSwitches::energy_tracking,
              "Accumulate elastic energy and dissipation per contact for the energy balance. auto: on "
              "when Output/energy balance is true."),
       effect(
           "rolling resistance", &dem::EffectSwitches::rolling_resistance,
           "Rolling resistance at every contact: elastic-plastic spring-dashpot (Iwashita and Oda "
           "1998; Ai et al. 2011, model C), |M_r| <= mu_r R* F_n. Not part of Yan and Regueiro's law: auto is"
           " off. Needs rotation."),
       effect("twisting resistance", &dem::EffectSwitches::twisting_resistance,
              "Twisting resistance at every contact: Hertz–Mindlin torsion of the contact circle (Lubkin "
              "1951; Johnson 1985, 7.4), stiffness 16/3 G a^3, full slip at 3 pi/16 mu a F_n, with the "
              "rolling dashpot's damping ratio. Stops grains spinning about a contact normal (needles, "
              "discs). Not part of Yan and Regueiro's law: auto is off. Needs rolling resistance.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
