#include "dem/engine/guards.h"

#include <algorithm>
#include <sstream>

#include "dem/scene/weight_overlap.h"
#include "dem/time_step.h"

namespace upgrain::dem {

std::string non_finite_state(const ParticleStore& p, int n_owned, long step, double time) {
  for (int i = 0; i < n_owned; ++i) {
    const bool orientation_ok = !p.has_shapes() || p.orientation[i].coeffs().allFinite();
    if (p.x[i].allFinite() && p.v[i].allFinite() && p.omega[i].allFinite() && orientation_ok) continue;
    std::ostringstream m;
    m << "particle " << p.id[i] << " has a non-finite position, velocity or orientation at step " << step
      << " (t = " << time << " s)";
    return m.str();
  }
  return {};
}

std::string runaway_overlap(double ratio, double limit, long step, double time, const SceneConfig& scene,
                            const OverlapSite& site, const AssemblyLoad& load) {
  if (!(ratio > limit)) return {};
  std::ostringstream m;
  m.precision(3);
  m << "runaway overlap at step " << step << " (t = " << time << " s): an overlap";
  const bool at_wall = site.particle >= 0 && site.partner < 0;
  if (site.particle >= 0) {
    m << " of particle " << site.particle << " with ";
    if (at_wall)
      m << "wall '" << site.wall << "'";
    else
      m << "particle " << site.partner;
  }
  m << " reached " << ratio << " of a radius (limit " << limit << "); ";
  // An overlap of a whole smallest semi-axis at a wall: a sphere's centre has reached the
  // plane. The grain is being lost through the wall, which no contact law can push back
  // reliably from there (the law is far outside its validity).
  if (at_wall && ratio >= 1.0)
    m << "particle " << site.particle << " is passing through wall '" << site.wall << "'; ";
  // Two causes look alike here: grains too soft to carry their weight sink into each other at
  // any time step, while a time step too large lets fast contacts overshoot. The overlap the
  // weight alone gives by the contact law tells them apart.
  const double weight = weight_overlap_ratio(scene);
  const double stressed = stress_overlap_ratio(scene, load);
  if (weight > kStaticOverlapBound) {
    m << "the grains are too soft for their weight: by the " << scene.contact_law
      << " law a grain's weight alone presses it " << weight
      << " of a radius into the floor (DEM keeps static "
      << "overlaps below " << kStaticOverlapBound
      << "), and a bed stacks many; raise Particles/youngs modulus "
      << "(now " << scene.particles.material.youngs_modulus
      << " Pa) or the law's stiffness, not the time step";
  } else if (stressed > kStaticOverlapBound) {
    // A cell that carries a stress presses its grains into each other more as the stress grows;
    // its force chains carry several times the mean force, and the largest overlap follows.
    m << "the grains are too soft for the stress they carry: at the cell's mean stress " << load.pressure
      << " Pa (coordination " << load.coordination << ", solid fraction " << load.solid_fraction << ") the "
      << scene.contact_law << " law gives a mean contact overlap of " << stressed
      << " of a radius (DEM keeps static overlaps below " << kStaticOverlapBound
      << "), and force chains carry several times the mean force; raise Particles/youngs modulus (now "
      << scene.particles.material.youngs_modulus
      << " Pa; Hertz overlaps fall as its -2/3 power) or the law's stiffness, not the time step";
  } else if (const TimeStepEstimate ts = estimate_time_step(scene);
             impact_overlap_ratio(scene, ts.impact_speed) > limit) {
    // The law itself gives this overlap at the scene's impact speed: no time step helps.
    m << "the grains are too soft for the impacts of this scene: by the " << scene.contact_law
      << " law a grain hitting the floor at the expected impact speed " << ts.impact_speed << " m/s sinks "
      << impact_overlap_ratio(scene, ts.impact_speed)
      << " of a radius into it; raise Particles/youngs modulus (now "
      << scene.particles.material.youngs_modulus << " Pa) or lower the impact speed, not the time step";
  } else {
    m << "the time step " << scene.time_step << " s (safe " << estimate_time_step(scene).safe_step
      << " s) is too large for the impacts of this scene, or a particle was placed inside another (a grain's "
      << "weight alone gives an overlap of " << weight << " of a radius)";
  }
  return m.str();
}

std::string lost_particles(long count, long expected, long step) {
  if (count == expected) return {};
  std::ostringstream m;
  m << "parallel run: " << count << " particles after the migration at step " << step << ", expected "
    << expected;
  return m.str();
}

std::string inconsistent_state(const ParticleStore& sorted, long expected_count, double mass,
                               double expected_mass, long step) {
  return inconsistent_state(static_cast<long>(sorted.size()),
                            std::adjacent_find(sorted.id.begin(), sorted.id.end()) == sorted.id.end(),
                            expected_count, mass, expected_mass, step);
}

std::string inconsistent_state(long n, bool unique, long expected_count, double mass, double expected_mass,
                               long step) {
  if (n == expected_count && unique && mass == expected_mass) return {};
  std::ostringstream m;
  m.precision(17);
  m << "parallel run: the gathered state at step " << step << " has " << n << " particles"
    << (unique ? "" : " with repeated ids") << " of mass " << mass << " kg; expected " << expected_count
    << " particles of mass " << expected_mass << " kg";
  return m.str();
}

}  // namespace upgrain::dem
