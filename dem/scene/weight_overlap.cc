#include "dem/scene/weight_overlap.h"

#include <numbers>

#include "dem/contact/contact_laws.h"
#include "dem/core/material.h"

namespace upgrain::dem {

namespace {

// The overlap at which `grows` (the law's force or energy, growing with the overlap) reaches
// `target`, as a fraction of the radius r: bisection on [0, 10 r] (beyond, the grain is a
// puddle).
template <class Grows>
double overlap_ratio_where(const Grows& grows, double target, double r) {
  double lo = 0.0, hi = 10.0 * r;
  if (grows(hi) < target) return hi / r;
  for (int k = 0; k < 200 && hi - lo > 1e-13 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (grows(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) / r;
}

}  // namespace

double weight_overlap_ratio(const SceneConfig& s) {
  if (!s.effects.gravity || s.gravity <= 0.0) return 0.0;
  const double r = s.particles.largest_radius();
  const double mass = s.particles.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double weight = mass * s.gravity;
  ContactMaterial m = ContactMaterial::from(s.particles.material, s.friction, s.damping_ratio);
  return with_contact_law(s.contact_law, [&]<class Law>() {
    Law::Normal::constants(s.law_parameters, m);
    // A grain on the floor: R* = R, m* = m (the wall does not move).
    const ContactParameters p{m.e_star_pw,     m.g_star_pw, r,     mass, s.friction,
                              s.damping_ratio, s.time_step, m.k_n, m.k_t};
    const auto force = [&](double delta) { return Law::Normal::response(p, delta).force; };
    return overlap_ratio_where(force, weight, r);
  });
}

double impact_overlap_ratio(const SceneConfig& s, double speed) {
  const double r = s.particles.gradation.empty() ? s.particles.radius : s.particles.gradation.back().radius;
  const double mass = s.particles.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double kinetic = 0.5 * mass * speed * speed;
  if (!(kinetic > 0.0)) return 0.0;
  ContactMaterial m = ContactMaterial::from(s.particles.material, s.friction, s.damping_ratio);
  return with_contact_law(s.contact_law, [&]<class Law>() {
    Law::Normal::constants(s.law_parameters, m);
    const ContactParameters p{m.e_star_pw,     m.g_star_pw, r,     mass, s.friction,
                              s.damping_ratio, s.time_step, m.k_n, m.k_t};
    const auto energy = [&](double delta) {
      return Law::Normal::energy(Law::Normal::response(p, delta), delta);
    };
    return overlap_ratio_where(energy, kinetic, r);
  });
}

}  // namespace upgrain::dem
