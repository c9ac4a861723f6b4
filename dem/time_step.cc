#include "dem/time_step.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem/contact/hertz_mindlin.h"
#include "dem/scene/fill.h"

namespace upgrain::dem {

double expected_impact_speed(const SceneConfig& s, double fill_top) {
  const double g = s.effects.gravity ? s.gravity : 0.0;
  const double v0 = s.fill.velocity.norm() + std::sqrt(3.0) * s.fill.velocity_jitter;
  return v0 + std::sqrt(2.0 * g * std::max(fill_top, 0.0));
}

TimeStepEstimate estimate_time_step(const SceneConfig& s) {
  const Material& m = s.particles.material;
  double r_min = s.particles.radius;
  if (!s.particles.gradation.empty()) r_min = s.particles.gradation.front().radius;
  const double nu = m.poisson_ratio;
  // Ellipsoids (docs/ellipsoids.md): the Rayleigh time of the thinnest semi-axis c, and the
  // Hertz time of the stiffest contact, at the flattest point of a grain (Gaussian radius
  // a b / c at the c pole) with the lightest grain's mass. Spheres: thin = flat = mass = 1.
  double thin = 1.0, flat = 1.0, mass_factor = 1.0;
  for (const GrainShape& g : s.particles.shapes) {
    thin = std::min(thin, g.c_over_a);
    flat = std::max(flat, g.b_over_a / g.c_over_a);
    mass_factor = std::min(mass_factor, g.b_over_a * g.c_over_a);
  }
  TimeStepEstimate e;
  e.rayleigh_time =
      std::numbers::pi * thin * r_min * std::sqrt(m.density / m.shear_modulus()) / (0.1631 * nu + 0.8766);
  e.impact_speed = s.time_step_rule.impact_speed > 0.0 ? s.time_step_rule.impact_speed
                                                       : expected_impact_speed(s, fill_top_height(s));
  const double v = std::max(e.impact_speed, 1e-3);  // a resting bed still has contacts
  const double mass = mass_factor * m.density * 4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min;
  const ContactMaterial cm = ContactMaterial::from(m, s.friction, s.damping_ratio);
  const double t_pp = hertz::contact_duration(cm.e_star_pp, 0.5 * flat * r_min, 0.5 * mass, v);
  const double t_pw = hertz::contact_duration(cm.e_star_pw, flat * r_min, mass, v);
  e.hertz_time = std::min(t_pp, t_pw);
  const double by_rayleigh = s.time_step_rule.rayleigh_fraction * e.rayleigh_time;
  const double by_hertz = s.time_step_rule.hertz_fraction * e.hertz_time;
  e.safe_step = std::min(by_rayleigh, by_hertz);
  e.limiting = by_rayleigh <= by_hertz ? "Rayleigh" : "Hertz";
  return e;
}

}  // namespace upgrain::dem
