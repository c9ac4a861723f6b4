#include "dem/engine/unbalanced_force.h"

#include "dem/core/error.h"
#include "dem/engine/particle_sums.h"
#include "dem/engine/simulation.h"

namespace upgrain::dem {

double unbalanced_force_ratio(std::span<const Vec3> forces, std::span<const ContactSample> contacts) {
  double resultant = 0.0;
  for (const Vec3& f : forces) resultant += f.norm();
  double contact = 0.0;
  long count = 0;
  for (const ContactSample& c : contacts) {
    if (c.with_wall() || static_cast<std::size_t>(c.a) >= forces.size()) continue;
    contact += c.force_on_a.norm();
    ++count;
  }
  if (forces.empty() || count == 0 || contact == 0.0) return 0.0;
  return (resultant / static_cast<double>(forces.size())) / (contact / static_cast<double>(count));
}

double unbalanced_force_ratio(const Simulation& sim) {
  if (!sim.contacts_recorded()) throw Error("unbalanced force: no contacts recorded at the last step");
  const ParticleStore& p = sim.particles();
  const int n = sim.owned();
  const Vec3 g = sim.gravity();
  enum { kResultant, kContact, kCount };
  ParticleSums sums(sim.summation(), 3, n);
  for (int i = 0; i < n; ++i)
    sums.add(kResultant, i, (p.force[i] + p.mass(static_cast<std::size_t>(i)) * g).norm());
  for (const ContactSample& c : sim.contacts()) {
    if (c.with_wall() || c.a >= n) continue;
    sums.add(kContact, c.a, c.force_on_a.norm());
    sums.add(kCount, c.a, 1.0);
  }
  const std::vector<double> t = sums.totals(sim.comm());
  if (sim.particle_count() == 0 || t[kCount] == 0.0 || t[kContact] == 0.0) return 0.0;
  return (t[kResultant] / static_cast<double>(sim.particle_count())) / (t[kContact] / t[kCount]);
}

}  // namespace upgrain::dem
