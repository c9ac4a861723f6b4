// Insertion during the run: the engine's side (simulation.h, insert(); docs/insertion.md).
#include <algorithm>
#include <sstream>

#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "dem/parallel/exchange.h"
#include "dem/parallel/records.h"

namespace upgrain::dem {

void Simulation::insert(const ParticleStore& grains) {
  // `grains` is the same on every rank: so are these checks, and the errors.
  for (std::size_t k = 0; k < grains.size(); ++k) {
    const GlobalId expected = static_cast<GlobalId>(n_global_) + static_cast<GlobalId>(k);
    std::ostringstream m;
    if (grains.id[k] != expected)
      m << "insert: grain " << k << " of the batch has id " << grains.id[k] << ", expected " << expected
        << " (ids follow the " << n_global_ << " grains in the scene)";
    else if (grains.radius[k] > max_radius_)
      m << "insert: grain " << grains.id[k] << " (radius " << grains.radius[k]
        << " m) is larger than the scene's largest grain (" << max_radius_
        << " m), for which the interaction range was chosen";
    else if (!grains.x[k].allFinite() || !grains.v[k].allFinite())
      m << "insert: grain " << grains.id[k] << " has a non-finite position or velocity";
    if (!m.str().empty()) throw Error(m.str());
  }
  if (grains.has_shapes() && !shapes_)
    throw Error("insert: ellipsoids into a scene of spheres (Particles/shapes names no ellipsoid)");
  const Decomposition& dec = domain_->decomposition();
  for (std::size_t k = 0; k < grains.size(); ++k) {
    // The energy reference takes the grain's energy as it enters (docs/integrator.md): the
    // balance E(t) - E(0) then measures the integration, not the pour.
    const double m = grains.mass(k);
    e0_.kinetic_translational += 0.5 * m * grains.v[k].squaredNorm();
    if (rotation_) e0_.kinetic_rotational += grains.rotational_energy(k);
    e0_.potential += -m * g_.dot(grains.x[k]);
    // The lost-particle guard's mass, summed in id order as whole_state() sums it.
    if (reference_mass_ >= 0.0) reference_mass_ += m;
    if (dec.owner_of(grains.x[k]) != dec.rank()) continue;
    const StateRecord r = pack_state(grains, k);
    append_state(arrivals_, r);
    if (shapes_) append_shape(arrivals_, grains.has_shapes() ? pack_shape(grains, k) : sphere_shape(r));
  }
  n_global_ += static_cast<long>(grains.size());
  // Every rank rebuilds at the next step, which joins the grains to the lists.
  if (grains.size() > 0) rebuild_pending_ = arrivals_pending_ = true;
}

std::vector<BoundingSphere> Simulation::bounding_spheres_in(const Box& box) const {
  struct Record {
    GlobalId gid;
    double x[3];
    double radius;
  };
  std::vector<Record> mine;
  for (int i = 0; i < n_owned_; ++i) {
    const Vec3& x = p_.x[i];
    const Vec3 nearest = x.cwiseMax(box.lo).cwiseMin(box.hi);
    if ((x - nearest).squaredNorm() >= p_.radius[i] * p_.radius[i]) continue;
    Record r{p_.id[i], {}, p_.radius[i]};
    put(r.x, x);
    mine.push_back(r);
  }
  std::vector<Record> all = gather_to_root(mine, comm());
  long n = static_cast<long>(all.size());
  MPI_Bcast(&n, 1, MPI_LONG, 0, comm());
  all.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(all.data(), static_cast<int>(all.size() * sizeof(Record)), MPI_BYTE, 0, comm());
  std::sort(all.begin(), all.end(), [](const Record& a, const Record& b) { return a.gid < b.gid; });
  std::vector<BoundingSphere> out;
  out.reserve(all.size());
  for (const Record& r : all) out.push_back({get(r.x), r.radius});
  return out;
}

}  // namespace upgrain::dem
