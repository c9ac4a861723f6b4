#include "dem/engine/unbalanced_force.h"

#include <vector>

#include "dem/core/error.h"
#include "dem/engine/particle_sums.h"
#include "dem/engine/simulation.h"

namespace upgrain::dem {

namespace {

enum Term { kResultant, kContact, kCount };

// The ratio's terms, each handed to add(term, grain, value) with the grain it belongs to: every
// owned grain's |F|, and each counted contact's |f| and 1 with its first grain (a pair is recorded
// once, with its first grain; wall contacts do not count).
template <class Add>
void add_terms(std::span<const Vec3> resultants, std::span<const ContactSample> contacts, Add&& add) {
  for (std::size_t i = 0; i < resultants.size(); ++i)
    add(kResultant, static_cast<int>(i), resultants[i].norm());
  for (const ContactSample& c : contacts) {
    if (c.with_wall() || c.a < 0 || static_cast<std::size_t>(c.a) >= resultants.size()) continue;
    add(kContact, c.a, c.force_on_a.norm());
    add(kCount, c.a, 1.0);
  }
}

// Yade's unbalancedForce from the sums: the mean |F| of `grains` over the mean |f| of the contacts.
double ratio(double resultant, double contact, double count, double grains) {
  if (grains == 0.0 || count == 0.0 || contact == 0.0) return 0.0;
  return (resultant / grains) / (contact / count);
}

}  // namespace

double unbalanced_force_ratio(std::span<const Vec3> forces, std::span<const ContactSample> contacts) {
  double t[3] = {0.0, 0.0, 0.0};
  add_terms(forces, contacts, [&](int term, int, double value) { t[term] += value; });
  return ratio(t[kResultant], t[kContact], t[kCount], static_cast<double>(forces.size()));
}

double unbalanced_force_ratio(const Simulation& sim) {
  if (!sim.contacts_recorded()) throw Error("unbalanced force: no contacts recorded at the last step");
  const ParticleStore& p = sim.particles();
  const int n = sim.owned();
  std::vector<Vec3> resultants(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    resultants[i] = p.force[i] + p.mass(static_cast<std::size_t>(i)) * sim.gravity();
  ParticleSums sums(sim.summation(), 3, n);
  add_terms(resultants, sim.contacts(),
            [&](int term, int grain, double value) { sums.add(term, grain, value); });
  const std::vector<double> t = sums.totals(sim.comm());
  return ratio(t[kResultant], t[kContact], t[kCount], static_cast<double>(sim.particle_count()));
}

}  // namespace upgrain::dem
