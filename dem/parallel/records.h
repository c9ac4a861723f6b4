#pragma once
// Flat, trivially copyable message records of the parallel engine: they travel as bytes
// (MPI_BYTE), so no MPI datatype has to be kept in step with them.
#include <type_traits>

#include "dem/core/particle_store.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// A ghost at a rebuild: what a neighbour needs to evaluate the pair law.
struct GhostRecord {
  GlobalId gid;
  double radius, inv_mass, inv_inertia;
  double x[3], v[3], omega[3];
};

// A ghost's refresh between rebuilds: the state that changes every step.
struct MotionRecord {
  double x[3], v[3], omega[3];
};

// A whole particle: migration and gathering.
struct StateRecord {
  GlobalId gid;
  double radius, inv_mass, inv_inertia;
  double x[3], v[3], omega[3], force[3], torque[3];
};

// One tangential spring keyed by global ids: a pair (a < b), force on a; or a wall
// contact of particle a with wall w, stored as b = -1 - w.
struct SpringRecord {
  GlobalId a, b;
  double force[3];
  double stiffness;
  bool operator<(const SpringRecord& o) const { return a < o.a || (a == o.a && b < o.b); }
  bool same_key(const SpringRecord& o) const { return a == o.a && b == o.b; }
};

// One contact keyed by global ids (a < b, force on a; or wall w as b = -1 - w), for
// gathered output.
struct ContactRecord {
  GlobalId a, b;
  double point[3], force[3];
  bool operator<(const ContactRecord& o) const { return a < o.a || (a == o.a && b < o.b); }
};

static_assert(std::is_trivially_copyable_v<ContactRecord>);
static_assert(std::is_trivially_copyable_v<GhostRecord> && std::is_trivially_copyable_v<MotionRecord> &&
              std::is_trivially_copyable_v<StateRecord> && std::is_trivially_copyable_v<SpringRecord>);

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
}

}  // namespace upgrain::dem
