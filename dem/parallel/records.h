#pragma once
// Flat, trivially copyable message records of the parallel engine: they travel as bytes
// (MPI_BYTE), so no MPI datatype has to be kept in step with them.
#include <cstdint>
#include <type_traits>

#include "dem/core/particle_store.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// A ghost's refresh between rebuilds: the state that changes every step.
struct MotionRecord {
  double x[3], v[3], omega[3];
};

// A whole particle: migration, ghosts at a rebuild (their forces are the force loop's to
// set), and gathering.
struct StateRecord {
  GlobalId gid;
  double radius, inv_mass, inv_inertia;
  double x[3], v[3], omega[3], force[3], torque[3];
  std::int32_t image[3];  // periodic image counter (dem/core/periodic_cell.h)
};

// The shape of an ellipsoid scene's particle (every grain; spheres as a = b = c): sent next
// to a StateRecord, in the same order, only when the scene has shapes, so
// sphere runs send nothing more.
struct ShapeRecord {
  double semi_axes[3], orientation[4], inertia_body[3];  // orientation as x, y, z, w
  ShapeKind kind;
};

// A ghost's orientation refresh, next to its MotionRecord (ellipsoid scenes).
struct OrientationRecord {
  double q[4];  // x, y, z, w
};

// One contact keyed by global ids (a < b, force on a; or wall w as b = -1 - w), for
// gathered output.
struct ContactRecord {
  GlobalId a, b;
  double point[3], force[3];
  bool operator<(const ContactRecord& o) const { return a < o.a || (a == o.a && b < o.b); }
};

static_assert(std::is_trivially_copyable_v<ContactRecord>);
static_assert(std::is_trivially_copyable_v<ShapeRecord> && std::is_trivially_copyable_v<OrientationRecord>);
static_assert(std::is_trivially_copyable_v<MotionRecord> && std::is_trivially_copyable_v<StateRecord>);

inline void put(double* out, const Vec3& v) { out[0] = v[0], out[1] = v[1], out[2] = v[2]; }
inline Vec3 get(const double* in) { return Vec3(in[0], in[1], in[2]); }

// Particle i of a store as a whole-particle record, and back (migration, gathering).
inline StateRecord pack_state(const ParticleStore& p, std::size_t i) {
  StateRecord r{};
  r.gid = p.id[i];
  r.radius = p.radius[i];
  r.inv_mass = p.inv_mass[i];
  r.inv_inertia = p.inv_inertia[i];
  put(r.x, p.x[i]);
  put(r.v, p.v[i]);
  put(r.omega, p.omega[i]);
  put(r.force, p.force[i]);
  put(r.torque, p.torque[i]);
  for (int d = 0; d < 3; ++d) r.image[d] = p.image[i][d];
  return r;
}

inline void append_state(ParticleStore& p, const StateRecord& r) {
  p.id.push_back(r.gid);
  p.radius.push_back(r.radius);
  p.inv_mass.push_back(r.inv_mass);
  p.inv_inertia.push_back(r.inv_inertia);
  p.x.push_back(get(r.x));
  p.v.push_back(get(r.v));
  p.omega.push_back(get(r.omega));
  p.force.push_back(get(r.force));
  p.torque.push_back(get(r.torque));
  p.image.push_back({r.image[0], r.image[1], r.image[2]});
}

}  // namespace upgrain::dem

namespace upgrain::dem {

inline void put(double* out, const Eigen::Quaterniond& q) {
  out[0] = q.x(), out[1] = q.y(), out[2] = q.z(), out[3] = q.w();
}
inline Eigen::Quaterniond get_quaternion(const double* in) {
  return Eigen::Quaterniond(in[3], in[0], in[1], in[2]);
}

// The shape of particle i of a store that has shapes, and back.
inline ShapeRecord pack_shape(const ParticleStore& p, std::size_t i) {
  ShapeRecord r{};
  r.kind = p.shape[i];
  put(r.semi_axes, p.semi_axes[i]);
  put(r.orientation, p.orientation[i]);
  put(r.inertia_body, p.inertia_body[i]);
  return r;
}

inline void append_shape(ParticleStore& p, const ShapeRecord& r) {
  p.shape.push_back(r.kind);
  p.semi_axes.push_back(get(r.semi_axes));
  p.orientation.push_back(get_quaternion(r.orientation));
  p.inertia_body.push_back(get(r.inertia_body));
}

// The shape record of a sphere (a = b = c, no turn), for a sphere joining grains with shapes.
inline ShapeRecord sphere_shape(const StateRecord& s) {
  ShapeRecord r{};
  r.kind = ShapeKind::sphere;
  for (int d = 0; d < 3; ++d) {
    r.semi_axes[d] = s.radius;
    r.inertia_body[d] = 1.0 / s.inv_inertia;
  }
  r.orientation[3] = 1.0;  // x, y, z, w: the identity
  return r;
}

// Every array of a store (the shape arrays when present) cut to its first n particles.
inline void truncate_store(ParticleStore& p, std::size_t n) {
  p.id.resize(n);
  p.radius.resize(n);
  p.inv_mass.resize(n);
  p.inv_inertia.resize(n);
  p.x.resize(n);
  p.v.resize(n);
  p.omega.resize(n);
  p.force.resize(n);
  p.torque.resize(n);
  p.image.resize(n);
  if (p.has_shapes()) {
    p.shape.resize(n);
    p.semi_axes.resize(n);
    p.orientation.resize(n);
    p.inertia_body.resize(n);
  }
}

// Particle `from` copied over particle `to` (compaction).
inline void copy_particle(ParticleStore& p, std::size_t from, std::size_t to) {
  p.id[to] = p.id[from];
  p.radius[to] = p.radius[from];
  p.inv_mass[to] = p.inv_mass[from];
  p.inv_inertia[to] = p.inv_inertia[from];
  p.x[to] = p.x[from];
  p.v[to] = p.v[from];
  p.omega[to] = p.omega[from];
  p.force[to] = p.force[from];
  p.torque[to] = p.torque[from];
  p.image[to] = p.image[from];
  if (p.has_shapes()) {
    p.shape[to] = p.shape[from];
    p.semi_axes[to] = p.semi_axes[from];
    p.orientation[to] = p.orientation[from];
    p.inertia_body[to] = p.inertia_body[from];
  }
}

}  // namespace upgrain::dem
