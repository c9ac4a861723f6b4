#include "dem/core/particle_store.h"

#include <algorithm>
#include <numbers>

namespace upgrain::dem {

namespace {
template <class T>
void apply_permutation(std::vector<T>& a, const std::vector<int>& perm, std::vector<T>& scratch) {
  scratch.resize(a.size());
  for (std::size_t k = 0; k < perm.size(); ++k) scratch[k] = a[perm[k]];
  a.swap(scratch);
}
}  // namespace

void ParticleStore::reserve(std::size_t n) {
  id.reserve(n);
  radius.reserve(n);
  inv_mass.reserve(n);
  inv_inertia.reserve(n);
  x.reserve(n);
  v.reserve(n);
  omega.reserve(n);
  force.reserve(n);
  torque.reserve(n);
}

void ParticleStore::add_sphere(GlobalId gid, double r, double density, const Vec3& pos, const Vec3& vel,
                               const Vec3& ang_vel) {
  const double m = density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  id.push_back(gid);
  radius.push_back(r);
  inv_mass.push_back(1.0 / m);
  inv_inertia.push_back(1.0 / (0.4 * m * r * r));
  x.push_back(pos);
  v.push_back(vel);
  omega.push_back(ang_vel);
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
}

void ParticleStore::permute(const std::vector<int>& perm) {
  std::vector<GlobalId> s_id;
  std::vector<double> s_d;
  std::vector<Vec3> s_v;
  apply_permutation(id, perm, s_id);
  apply_permutation(radius, perm, s_d);
  apply_permutation(inv_mass, perm, s_d);
  apply_permutation(inv_inertia, perm, s_d);
  apply_permutation(x, perm, s_v);
  apply_permutation(v, perm, s_v);
  apply_permutation(omega, perm, s_v);
  apply_permutation(force, perm, s_v);
  apply_permutation(torque, perm, s_v);
}

double ParticleStore::max_radius() const {
  return radius.empty() ? 0.0 : *std::max_element(radius.begin(), radius.end());
}
double ParticleStore::min_radius() const {
  return radius.empty() ? 0.0 : *std::min_element(radius.begin(), radius.end());
}

}  // namespace upgrain::dem
