#include "dem/scene/weight_overlap.h"

#include <numbers>
#include <vector>

#include "dem/contact/contact_laws.h"

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

// The radius half the grains' mass is finer than (a gradation's d50 / 2, by linear interpolation
// on the curve), or the mean radius of a packing.
double median_radius(const ParticleSpec& p) {
  if (p.packing && p.packing->size() > 0) {
    double sum = 0.0;
    for (const double r : p.packing->radius) sum += r;
    return sum / static_cast<double>(p.packing->size());
  }
  const std::vector<GradationPoint>& g = p.gradation;
  if (g.empty()) return p.radius;
  for (std::size_t k = 1; k < g.size(); ++k)
    if (g[k].fraction_passing >= 0.5) {
      const double span = g[k].fraction_passing - g[k - 1].fraction_passing;
      const double t = span > 0.0 ? (0.5 - g[k - 1].fraction_passing) / span : 1.0;
      return g[k - 1].radius + t * (g[k].radius - g[k - 1].radius);
    }
  return g.back().radius;
}

double grain_mass(const SceneConfig& s, double r) {
  return s.particles.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

// What a grain of radius r presses against: the floor (R* = R, m* = m: the wall does not move),
// or an equal grain (R* = R / 2, m* = m / 2).
enum class Partner { wall, grain };

// The overlap at which the law's normal force against `partner` reaches `force`, as a fraction of r.
double overlap_ratio_at_force(const SceneConfig& s, Partner partner, double r, double force) {
  const double share = partner == Partner::wall ? 1.0 : 0.5;
  const ContactParameters p{.r_star = share * r,
                            .m_star = share * grain_mass(s, r),
                            .friction = s.friction,
                            .zeta = s.damping_ratio,
                            .dt = s.time_step};
  return with_contact_law(s.contact_law, [&]<class Law>() {
    const auto both = Law::Normal::constants(s.particles.material, s.law_parameters);
    const auto& c = partner == Partner::wall ? both.wall : both.pair;
    const auto grows = [&](double delta) { return Law::Normal::response(c, p, delta).force; };
    return overlap_ratio_where(grows, force, r);
  });
}

}  // namespace

double weight_overlap_ratio(const SceneConfig& s) {
  if (!s.effects.gravity || s.gravity <= 0.0) return 0.0;
  const double r = s.particles.largest_radius();
  return overlap_ratio_at_force(s, Partner::wall, r, grain_mass(s, r) * s.gravity);
}

double impact_overlap_ratio(const SceneConfig& s, double speed) {
  const double r = s.particles.gradation.empty() ? s.particles.radius : s.particles.gradation.back().radius;
  const double mass = grain_mass(s, r);
  const double kinetic = 0.5 * mass * speed * speed;
  if (!(kinetic > 0.0)) return 0.0;
  return with_contact_law(s.contact_law, [&]<class Law>() {
    const auto c = Law::Normal::constants(s.particles.material, s.law_parameters).wall;
    const ContactParameters p{
        .r_star = r, .m_star = mass, .friction = s.friction, .zeta = s.damping_ratio, .dt = s.time_step};
    const auto energy = [&](double delta) {
      return Law::Normal::energy(Law::Normal::response(c, p, delta), delta);
    };
    return overlap_ratio_where(energy, kinetic, r);
  });
}

double stress_overlap_ratio(const SceneConfig& s, const AssemblyLoad& load) {
  if (!(load.pressure > 0.0 && load.coordination > 0.0 && load.solid_fraction > 0.0)) return 0.0;
  const double r = median_radius(s.particles);
  const double mean_force =
      4.0 * std::numbers::pi * r * r * load.pressure / (load.coordination * load.solid_fraction);
  return overlap_ratio_at_force(s, Partner::grain, r, mean_force);
}

}  // namespace upgrain::dem
