#include "dem/engine/guards.h"

#include <algorithm>
#include <sstream>

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

std::string runaway_overlap(double ratio, double limit, long step, double time, double time_step) {
  if (!(ratio > limit)) return {};
  std::ostringstream m;
  m << "runaway overlap at step " << step << " (t = " << time << " s): an overlap reached " << ratio
    << " of a radius (limit " << limit << "); the time step " << time_step
    << " s is too large for this scene or a particle was placed inside another";
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
  const long n = static_cast<long>(sorted.size());
  const bool unique = std::adjacent_find(sorted.id.begin(), sorted.id.end()) == sorted.id.end();
  if (n == expected_count && unique && mass == expected_mass) return {};
  std::ostringstream m;
  m.precision(17);
  m << "parallel run: the gathered state at step " << step << " has " << n << " particles"
    << (unique ? "" : " with repeated ids") << " of mass " << mass << " kg; expected " << expected_count
    << " particles of mass " << expected_mass << " kg";
  return m.str();
}

}  // namespace upgrain::dem
