#include "dem/engine/unbalanced_force.h"

#include <vector>

#include "dem/core/error.h"
#include "dem/engine/particle_sums.h"
#include "dem/engine/simulation.h"

namespace upgrain::dem {

namespace {

enum Term { kResultant, kContact, kCount };

// The ratio's terms, each handed to add(term, grain, value) with the grain it belongs to: each of
// the n owned grains' |F| (resultant(i)), and each counted contact's |f| and 1 with its first
// grain (a pair is recorded once, with its first grain; wall contacts do not count).
template <class Resultant, class Add>
void add_terms(int n, Resultant&& resultant, std::span<const ContactSample> contacts, Add&& add) {
  for (int i = 0; i < n; ++i) add(kResultant, i, resultant(i).norm());
  for (const ContactSample& c : contacts) {
    if (c.with_wall() || c.a < 0 || c.a >= n) continue;
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
  add_terms(
      static_cast<int>(forces.size()), [&](int i) { return forces[static_cast<std::size_t>(i)]; }, contacts,
      [&](int term, int, double value) { t[term] += value; });
  return ratio(t[kResultant], t[kContact], t[kCount], static_cast<double>(forces.size()));
}

double unbalanced_force_ratio(const Simulation& sim) {
  if (!sim.contacts_recorded()) throw Error("unbalanced force: no contacts recorded at the last step");
  const ParticleStore& p = sim.particles();
  const Vec3 g = sim.gravity();
  ParticleSums sums(sim.summation(), 3, sim.owned());
  add_terms(
      sim.owned(), [&](int i) -> Vec3 { return p.force[i] + p.mass(static_cast<std::size_t>(i)) * g; },
      sim.contacts(), [&](int term, int grain, double value) { sums.add(term, grain, value); });
  const std::vector<double> t = sums.totals(sim.comm());
  return ratio(t[kResultant], t[kContact], t[kCount], static_cast<double>(sim.particle_count()));
}

}  // namespace upgrain::dem
