// The effect set derived from a scene (dem/scene/effect_choice.h): each entry follows the
// parameter that calls for it, an explicit setting wins, switching off what a parameter needs
// is refused, and a frictionless scene runs the force loop compiled without friction.
#include "dem/scene/effect_choice.h"

#include <gtest/gtest.h>

#include <string>

#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "dem/scene/fill.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

const EffectChoice& entry(const ChosenEffects& c, const std::string& name) {
  for (const EffectChoice& e : c.choices)
    if (e.entry == name) return e;
  throw std::runtime_error("no entry " + name);
}

std::string refusal(const SceneConfig& s, const EffectSwitches& sw, const EffectNeeds& needs = {}) {
  try {
    choose_effects(s, sw, needs);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(EffectChoice, TheDefaultSceneCallsForEveryEffectButRollingAndTwistingResistance) {
  const ChosenEffects c = choose_effects(SceneConfig{}, {}, {});
  EXPECT_TRUE(c.set.gravity);
  EXPECT_TRUE(c.set.friction);
  EXPECT_TRUE(c.set.damping);
  EXPECT_TRUE(c.set.wall_friction);
  EXPECT_TRUE(c.set.rotation);
  EXPECT_TRUE(c.set.energy_tracking);
  EXPECT_FALSE(c.set.rolling_resistance);
  EXPECT_FALSE(c.set.twisting_resistance);
  ASSERT_EQ(c.choices.size(), 8U);
  EXPECT_NE(entry(c, "tangential friction").reason.find("Contact/friction coefficient = 0.5"),
            std::string::npos);
}

TEST(EffectChoice, EachZeroParameterSwitchesItsEffectOff) {
  SceneConfig s;
  s.friction = 0.0;
  s.damping_ratio = 0.0;
  s.gravity = 0.0;
  for (double& mu : s.container.friction) mu = 0.0;
  const ChosenEffects c = choose_effects(s, {}, {false});
  EXPECT_FALSE(c.set.friction);
  EXPECT_FALSE(c.set.damping);
  EXPECT_FALSE(c.set.gravity);
  EXPECT_FALSE(c.set.wall_friction);
  EXPECT_FALSE(c.set.energy_tracking);
  // Frictionless spheres: no torque acts, so no rotation work.
  EXPECT_FALSE(c.set.rotation);
  EXPECT_NE(entry(c, "rotation").reason.find("frictionless spheres"), std::string::npos);
  EXPECT_NE(entry(c, "wall friction").reason.find("frictionless"), std::string::npos);
}

TEST(EffectChoice, OneFrictionalWallKeepsWallFriction) {
  SceneConfig s;
  for (double& mu : s.container.friction) mu = 0.0;
  s.container.friction[0] = 0.3;  // the floor
  EXPECT_TRUE(choose_effects(s, {}, {}).set.wall_friction);
}

TEST(EffectChoice, EllipsoidsRotateWithoutFriction) {
  SceneConfig s;
  s.friction = 0.0;
  for (double& mu : s.container.friction) mu = 0.0;
  s.particles.shapes = {ellipsoid_grain(0.8, 0.6, 1.0)};
  const ChosenEffects c = choose_effects(s, {}, {});
  EXPECT_TRUE(c.set.rotation);
  EXPECT_NE(entry(c, "rotation").reason.find("ellipsoids"), std::string::npos);
}

TEST(EffectChoice, AnExplicitSettingWins) {
  SceneConfig s;
  s.friction = 0.0;
  EffectSwitches sw;
  sw.friction = EffectSwitch::on;   // the friction code with mu = 0, if asked for
  sw.rotation = EffectSwitch::off;  // grains held from turning: a modelling choice
  sw.rolling_resistance = EffectSwitch::off;
  const ChosenEffects c = choose_effects(s, sw, {});
  EXPECT_TRUE(c.set.friction);
  EXPECT_FALSE(c.set.rotation);
  EXPECT_NE(entry(c, "tangential friction").reason.find("set in the scene"), std::string::npos);
}

TEST(EffectChoice, SwitchingOffWhatAParameterNeedsIsRefused) {
  const SceneConfig s;
  auto off = [](EffectSwitch EffectSwitches::*member) {
    EffectSwitches sw;
    sw.*member = EffectSwitch::off;
    return sw;
  };
  EXPECT_NE(
      refusal(s, off(&EffectSwitches::friction)).find("Effects/tangential friction = false contradicts"),
      std::string::npos);
  EXPECT_NE(refusal(s, off(&EffectSwitches::damping)).find("Contact/damping ratio = 0.5"), std::string::npos);
  EXPECT_NE(refusal(s, off(&EffectSwitches::wall_friction)).find("Effects/wall friction"), std::string::npos);
  EXPECT_NE(refusal(s, off(&EffectSwitches::gravity)).find("gravity acceleration"), std::string::npos);
  EXPECT_NE(refusal(s, off(&EffectSwitches::energy_tracking)).find("Output/energy balance"),
            std::string::npos);
  // Nothing needs them: no refusal.
  EXPECT_EQ(refusal(s, off(&EffectSwitches::rotation)), "");
  EXPECT_EQ(refusal(s, off(&EffectSwitches::rolling_resistance)), "");
}

TEST(EffectChoice, RollingResistanceNeedsRotation) {
  EffectSwitches sw;
  sw.rolling_resistance = EffectSwitch::on;
  EXPECT_TRUE(choose_effects(SceneConfig{}, sw, {}).set.rolling_resistance);
  sw.rotation = EffectSwitch::off;
  EXPECT_NE(refusal(SceneConfig{}, sw).find("Effects/rolling resistance needs Effects/rotation = true"),
            std::string::npos);
}

TEST(EffectChoice, TwistingResistanceNeedsRollingResistance) {
  EffectSwitches sw;
  sw.twisting_resistance = EffectSwitch::on;
  EXPECT_NE(
      refusal(SceneConfig{}, sw).find("Effects/twisting resistance needs Effects/rolling resistance = true"),
      std::string::npos);
  sw.rolling_resistance = EffectSwitch::on;
  const ChosenEffects c = choose_effects(SceneConfig{}, sw, {});
  EXPECT_TRUE(c.set.rolling_resistance);
  EXPECT_TRUE(c.set.twisting_resistance);
}

TEST(EffectChoice, SwitchesReadAsWritten) {
  EXPECT_EQ(parse_effect_switch("auto", "Effects/damping"), EffectSwitch::automatic);
  EXPECT_EQ(parse_effect_switch("true", "Effects/damping"), EffectSwitch::on);
  EXPECT_EQ(parse_effect_switch("false", "Effects/damping"), EffectSwitch::off);
  EXPECT_THROW(parse_effect_switch("yes", "Effects/damping"), Error);
}

TEST(EffectChoice, TheChoicesAreRecordedAsJson) {
  const ChosenEffects c = choose_effects(SceneConfig{}, {}, {});
  const std::string j = effects_json(c.choices);
  EXPECT_EQ(j.front(), '{');
  EXPECT_NE(
      j.find("\"tangential friction\": {\"on\": true, \"reason\": \"Contact/friction coefficient = 0.5\"}"),
      std::string::npos);
  EXPECT_NE(j.find("\"rolling resistance\": {\"on\": false"), std::string::npos);
}

// The engine runs what the scene calls for: a scene with friction 0 everywhere gets the
// instantiation of the force loop without tangential springs and without rotation work.
TEST(EffectChoice, AFrictionlessSceneRunsTheFrictionlessForceLoop) {
  SceneConfig s;
  s.particles.count = 50;
  s.friction = 0.0;
  for (double& mu : s.container.friction) mu = 0.0;
  s.effects = choose_effects(s, {}, {}).set;
  Simulation frictionless(s, fill_container(s));
  EXPECT_FALSE(frictionless.force_loop_effects().friction);
  EXPECT_FALSE(frictionless.force_loop_effects().wall_friction);
  EXPECT_FALSE(frictionless.force_loop_effects().rotation);
  EXPECT_TRUE(frictionless.force_loop_effects().damping);
  frictionless.step();
  EXPECT_EQ(frictionless.step_count(), 1);

  SceneConfig f;
  f.particles.count = 50;
  f.effects = choose_effects(f, {}, {}).set;
  const Simulation frictional(f, fill_container(f));
  EXPECT_TRUE(frictional.force_loop_effects().friction);
  EXPECT_TRUE(frictional.force_loop_effects().rotation);
}
