#include "dem/core/particle_store.h"

#include <algorithm>
#include <numbers>
#include <sstream>

#include "dem/core/error.h"

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
  image.reserve(n);
  if (has_shapes()) {
    shape.reserve(n);
    semi_axes.reserve(n);
    orientation.reserve(n);
    inertia_body.reserve(n);
  }
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
  image.push_back({0, 0, 0});
  if (has_shapes()) {
    shape.push_back(ShapeKind::sphere);
    semi_axes.push_back(Vec3::Constant(r));
    orientation.push_back(Eigen::Quaterniond::Identity());
    inertia_body.push_back(Vec3::Constant(0.4 * m * r * r));
  }
}

void ParticleStore::ensure_shapes() {
  if (has_shapes()) return;
  const std::size_t n = size();
  shape.assign(n, ShapeKind::sphere);
  semi_axes.resize(n);
  orientation.assign(n, Eigen::Quaterniond::Identity());
  inertia_body.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    semi_axes[i] = Vec3::Constant(radius[i]);
    inertia_body[i] = Vec3::Constant(1.0 / inv_inertia[i]);
  }
}

void ParticleStore::add_ellipsoid(GlobalId gid, const EllipsoidBody& body, const GrainMotion& motion) {
  const Vec3& ax = body.semi_axes;
  const double density = body.density;
  if (!(ax.z() > 0.0 && ax.y() >= ax.z() && ax.x() >= ax.y()) || !ax.allFinite()) {
    std::ostringstream m;
    m << "particle " << gid << ": semi-axes must satisfy a >= b >= c > 0, got " << ax.transpose();
    throw Error(m.str());
  }
  // The first ellipsoid: the spheres so far get their shapes too.
  ensure_shapes();
  const double a = ax.x(), b = ax.y(), c = ax.z();
  const double m = density * 4.0 / 3.0 * std::numbers::pi * a * b * c;
  // Principal moments of a solid ellipsoid: J_x = m (b^2 + c^2) / 5, and cyclically.
  const Vec3 j(0.2 * m * (b * b + c * c), 0.2 * m * (a * a + c * c), 0.2 * m * (a * a + b * b));
  id.push_back(gid);
  radius.push_back(a);
  inv_mass.push_back(1.0 / m);
  inv_inertia.push_back(3.0 / j.sum());
  x.push_back(motion.x);
  v.push_back(motion.v);
  omega.push_back(motion.omega);
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  image.push_back({0, 0, 0});
  shape.push_back(ShapeKind::ellipsoid);
  semi_axes.push_back(ax);
  orientation.push_back(body.orientation.normalized());
  inertia_body.push_back(j);
}

double ParticleStore::volume(std::size_t i) const {
  if (has_shapes()) return 4.0 / 3.0 * std::numbers::pi * semi_axes[i].prod();
  return 4.0 / 3.0 * std::numbers::pi * radius[i] * radius[i] * radius[i];
}

Mat3 ParticleStore::inertia_world(std::size_t i) const {
  if (!oriented(i)) return Mat3::Identity() / inv_inertia[i];
  const Mat3 r = orientation[i].toRotationMatrix();
  return r * inertia_body[i].asDiagonal() * r.transpose();
}

double ParticleStore::rotational_energy(std::size_t i, const Vec3& w) const {
  if (!oriented(i)) return 0.5 * w.squaredNorm() / inv_inertia[i];
  const Vec3 wb = orientation[i].conjugate() * w;
  return 0.5 * wb.dot(inertia_body[i].cwiseProduct(wb));
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
  std::vector<ImageCount> s_i;
  apply_permutation(image, perm, s_i);
  if (has_shapes()) {
    std::vector<Eigen::Quaterniond> s_q;
    std::vector<ShapeKind> s_k;
    apply_permutation(shape, perm, s_k);
    apply_permutation(semi_axes, perm, s_v);
    apply_permutation(inertia_body, perm, s_v);
    apply_permutation(orientation, perm, s_q);
  }
}

double ParticleStore::max_radius() const {
  return radius.empty() ? 0.0 : *std::max_element(radius.begin(), radius.end());
}
double ParticleStore::min_radius() const {
  return radius.empty() ? 0.0 : *std::min_element(radius.begin(), radius.end());
}

}  // namespace upgrain::dem
