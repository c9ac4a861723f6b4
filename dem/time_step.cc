#include "dem/time_step.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem/contact/contact_laws.h"
#include "dem/scene/fill.h"

namespace upgrain::dem {

double expected_impact_speed(const SceneConfig& s, double fill_top) {
  const double g = s.effects.gravity ? s.gravity : 0.0;
  double v0 = s.fill.velocity.norm() + std::sqrt(3.0) * s.fill.velocity_jitter;
  // A pour's grains fall from the top of its inlet with their own velocity (docs/insertion.md).
  if (s.insertion.enabled()) {
    fill_top = std::max(fill_top, s.insertion.inlet_hi.z());
    v0 = std::max(v0, s.insertion.velocity.norm());
  }
  return v0 + std::sqrt(2.0 * g * std::max(fill_top, 0.0));
}

TimeStepEstimate estimate_time_step(const SceneConfig& s) {
  SceneTimeScales t;
  t.material = s.particles.material;
  t.r_min = s.particles.smallest_radius();
  // Ellipsoids (docs/ellipsoids.md): the thinnest semi-axis c, the flattest point of a grain
  // (Gaussian radius a b / c at the c pole) and the lightest grain's mass. Spheres: 1.
  double mass_factor = 1.0;
  for (const GrainShape& g : s.particles.shapes) {
    const ShapeScales k = scales(g);
    t.thinnest = std::min(t.thinnest, k.thinnest);
    t.flattest = std::max(t.flattest, k.flattest);
    mass_factor = std::min(mass_factor, k.volume);
  }
  t.lightest = mass_factor * t.material.density * 4.0 / 3.0 * std::numbers::pi * t.r_min * t.r_min * t.r_min;
  TimeStepEstimate e;
  e.impact_speed = s.time_step_rule.impact_speed > 0.0 ? s.time_step_rule.impact_speed
                                                       : expected_impact_speed(s, fill_top_height(s));
  t.impact_speed = std::max(e.impact_speed, 1e-3);  // a resting bed still has contacts
  const LawInfo& law = find_contact_law(s.contact_law);
  const LawTimeLimit limit =
      law.time_limit(law.constants(t.material, s.law_parameters), t, s.time_step_rule.rayleigh_fraction,
                     s.time_step_rule.hertz_fraction);
  e.rayleigh_time = limit.rayleigh_time;
  e.contact_time = limit.contact_time;
  e.hertz_time = s.contact_law == HertzMindlin::name ? limit.contact_time : 0.0;
  e.safe_step = limit.safe_step;
  e.limiting = limit.limiting;
  return e;
}

}  // namespace upgrain::dem
