#include "upscale/cg/grain_state.h"

#include <algorithm>
#include <string>

#include "dem/core/error.h"

namespace upgrain::upscale::cg {

ReferencePositions reference_from(const dem::ParticleStore& p, double time) {
  ReferencePositions r;
  r.time = time;
  r.id = p.id;
  r.x = p.x;
  return r;
}

namespace {

void add_branch(GrainState& s, const Vec3& from, const Vec3& to, const Vec3& force,
                bool ends_at_grain = false) {
  s.branch_from.push_back(from);
  s.branch_to.push_back(to);
  s.branch_force.push_back(force);
  s.ends_at_grain.push_back(ends_at_grain ? 1 : 0);
  s.longest_branch = std::max(s.longest_branch, (to - from).norm());
}

// Whether the contact point c lies on the segment from a to b, to round-off (spheres: the
// point is a + (r_a - overlap / 2) n with n along b - a).
bool on_segment(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 l = b - a, d = c - a;
  const double l2 = l.squaredNorm();
  if (l2 == 0.0) return false;
  const double s = d.dot(l) / l2;
  return s >= 0.0 && s <= 1.0 && (d - s * l).squaredNorm() <= 1e-24 * l2;
}

}  // namespace

GrainState state_from(const dem::ParticleStore& p, const std::vector<dem::ContactRecord>& contacts,
                      const Vec3& gravity, double time, const ReferencePositions* reference) {
  GrainState s;
  s.time = time;
  s.gravity = gravity;
  const std::size_t n = p.size();
  s.id = p.id;
  s.x = p.x;
  s.v = p.v;
  s.acceleration.resize(n);
  s.mass.resize(n);
  s.volume.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.mass[i] = p.mass(i);
    s.volume[i] = p.volume(i);
    s.acceleration[i] = p.force[i] * p.inv_mass[i] + gravity;
  }
  if (reference) {
    s.with_displacement = true;
    s.displacement.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto it = std::lower_bound(reference->id.begin(), reference->id.end(), p.id[i]);
      if (it == reference->id.end() || *it != p.id[i])
        throw Error("coarse graining: grain " + std::to_string(p.id[i]) +
                    " is not in the reference state of t = " + std::to_string(reference->time) + " s");
      s.displacement[i] = p.x[i] - reference->x[static_cast<std::size_t>(it - reference->id.begin())];
    }
  }
  auto index = [&](GlobalId gid) {
    const auto it = std::lower_bound(p.id.begin(), p.id.end(), gid);
    if (it == p.id.end() || *it != gid)
      throw Error("coarse graining: contact with grain " + std::to_string(gid) +
                  ", which is not in the state");
    return static_cast<std::size_t>(it - p.id.begin());
  };
  s.branch_from.reserve(2 * contacts.size());
  s.branch_to.reserve(2 * contacts.size());
  s.branch_force.reserve(2 * contacts.size());
  for (const dem::ContactRecord& c : contacts) {
    const Vec3 point = dem::get(c.point), force = dem::get(c.force);
    const Vec3& xa = p.x[index(c.a)];
    if (c.b >= 0) {
      const Vec3& xb = p.x[index(c.b)];
      if (on_segment(xa, xb, point)) {
        add_branch(s, xa, xb, force, true);
      } else {
        add_branch(s, xa, point, force);
        add_branch(s, xb, point, -force);
      }
    } else {
      add_branch(s, xa, point, force);
      s.wall_point.push_back(point);
      s.wall_force.push_back(force);
    }
  }
  return s;
}

namespace {

bool near(const Vec3& x, const dem::Box& b, double range) {
  for (int d = 0; d < 3; ++d)
    if (x[d] < b.lo[d] - range || x[d] > b.hi[d] + range) return false;
  return true;
}

bool segment_near(const Vec3& a, const Vec3& c, const dem::Box& b, double range) {
  for (int d = 0; d < 3; ++d)
    if (std::max(a[d], c[d]) < b.lo[d] - range || std::min(a[d], c[d]) > b.hi[d] + range) return false;
  return true;
}

}  // namespace

GrainState part_near(const GrainState& s, const dem::Box& box, double range) {
  GrainState out;
  out.time = s.time;
  out.gravity = s.gravity;
  out.longest_branch = s.longest_branch;
  out.with_displacement = s.with_displacement;
  for (std::size_t i = 0; i < s.grains(); ++i) {
    if (!near(s.x[i], box, range)) continue;
    out.id.push_back(s.id[i]);
    out.x.push_back(s.x[i]);
    out.v.push_back(s.v[i]);
    out.acceleration.push_back(s.acceleration[i]);
    if (s.has_displacement()) out.displacement.push_back(s.displacement[i]);
    out.mass.push_back(s.mass[i]);
    out.volume.push_back(s.volume[i]);
  }
  for (std::size_t k = 0; k < s.branches(); ++k) {
    if (!segment_near(s.branch_from[k], s.branch_to[k], box, range)) continue;
    out.branch_from.push_back(s.branch_from[k]);
    out.branch_to.push_back(s.branch_to[k]);
    out.branch_force.push_back(s.branch_force[k]);
    out.ends_at_grain.push_back(s.ends_at_grain[k]);
  }
  for (std::size_t k = 0; k < s.wall_contacts(); ++k) {
    if (!near(s.wall_point[k], box, range)) continue;
    out.wall_point.push_back(s.wall_point[k]);
    out.wall_force.push_back(s.wall_force[k]);
  }
  return out;
}

}  // namespace upgrain::upscale::cg
