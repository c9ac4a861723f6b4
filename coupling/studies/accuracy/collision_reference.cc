#include "coupling/studies/accuracy/collision_reference.h"

#include <cmath>

#include "dem/contact/contact_laws.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

CollisionError collision_error(const dem::SceneConfig& scene, double radius, double speed, double dt) {
  dem::SceneConfig s = scene;
  s.effects = dem::EffectSet{};
  s.effects.gravity = false;
  s.effects.energy_tracking = false;
  s.friction = 0.0;
  s.damping_ratio = 0.0;
  s.time_step = dt;
  s.time_step_rule.allow_unsafe = true;
  const double density = s.particles.material.density;
  dem::ParticleStore p;
  const double gap = 1e-3 * radius;  // apart at the start, by less than one step of travel at most
  p.add_sphere(0, radius, density, dem::Vec3(-radius - gap, 0, 0), dem::Vec3(0.5 * speed, 0, 0),
               dem::Vec3::Zero());
  p.add_sphere(1, radius, density, dem::Vec3(radius + gap, 0, 0), dem::Vec3(-0.5 * speed, 0, 0),
               dem::Vec3::Zero());
  const double m_star = 0.5 * p.mass(0), r_star = 0.5 * radius;
  const dem::LawInfo& law = dem::find_contact_law(s.contact_law);
  const double exact =
      law.collision_duration(law.constants(s.particles.material, s.law_parameters), r_star, m_star, speed);
  dem::Simulation sim(s, p, std::vector<dem::PlaneWall>{});
  auto overlap = [&] {
    const dem::ParticleStore& q = sim.particles();
    return 2.0 * radius - (q.x[1] - q.x[0]).norm();
  };
  double start = -1.0, end = -1.0, before = overlap();
  const long limit = static_cast<long>(std::ceil(20.0 * exact / dt)) + 100;
  for (long k = 0; k < limit && end < 0.0; ++k) {
    const double t0 = sim.time();
    sim.step();
    const double now = overlap();
    // Linear interpolation of the overlap's zero within the step.
    if (start < 0.0 && before <= 0.0 && now > 0.0) start = t0 + dt * (-before) / (now - before);
    if (start >= 0.0 && before > 0.0 && now <= 0.0) end = t0 + dt * before / (before - now);
    before = now;
  }
  const dem::ParticleStore& q = sim.particles();
  CollisionError e;
  e.duration = std::abs((end - start) - exact) / exact;
  e.restitution = std::abs((q.v[1] - q.v[0]).x() / speed - 1.0);
  e.steps_in_contact = (end - start) / dt;
  return e;
}

}  // namespace upgrain::coupling
