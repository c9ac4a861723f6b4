#include "upscale/cg/grain_state.h"

#include <algorithm>
#include <string>

#include "dem/core/error.h"

namespace upgrain::upscale::cg {

ReferencePositions reference_from(const dem::ParticleStore& p, double time, const dem::PeriodicCell* cell) {
  ReferencePositions r;
  r.time = time;
  r.id = p.id;
  r.x = p.x;
  if (cell && cell->any()) r.image = p.image;
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

// x - X against the reference. In a periodic cell the grain followed from the image it was in
// at the reference, x + h (n - n0) - X (the strain's x*, docs/periodic.md, "Strain over a
// periodic cell"); without the reference's counters (a checkpoint written before they were
// kept) the minimum image, which folds a displacement beyond half a cell length.
Vec3 displacement(const dem::PeriodicCell* cell, const Vec3& x, const dem::ImageCount& n, const Vec3& x0,
                  const dem::ImageCount* n0) {
  if (!cell || !cell->any()) return x - x0;
  if (!n0) return dem::minimum_image(*cell, x - x0);
  const dem::ImageCount crossed{n[0] - (*n0)[0], n[1] - (*n0)[1], n[2] - (*n0)[2]};
  return dem::unwrapped(*cell, x, crossed) - x0;
}

// The contact point and b's centre next to a (minimum image): the recorded point lies near
// one of the two wrapped grains, not necessarily a. Exact on the cell's grid for the centres;
// the point moves by whole lattice vectors.
struct PairNearA {
  Vec3 point, xb;
};
PairNearA pair_near_a(const dem::PeriodicCell& cell, const Vec3& xa, const Vec3& xb, const Vec3& point) {
  const Vec3 c = xa + dem::minimum_image(cell, point - xa);
  return {c, c + dem::minimum_image(cell, xb - c)};
}

}  // namespace

GrainState state_from(const dem::ParticleStore& p, const std::vector<dem::ContactRecord>& contacts,
                      const Vec3& gravity, double time, const ReferencePositions* reference,
                      const dem::PeriodicCell* cell) {
  const bool periodic = cell && cell->any();
  GrainState s;
  if (periodic) s.cell = *cell;
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
      const auto k = static_cast<std::size_t>(it - reference->id.begin());
      s.displacement[i] = displacement(cell, p.x[i], p.image[i], reference->x[k],
                                       reference->image.empty() ? nullptr : &reference->image[k]);
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
    Vec3 point = dem::get(c.point);
    const Vec3 force = dem::get(c.force);
    const Vec3& xa = p.x[index(c.a)];
    if (c.b >= 0) {
      Vec3 xb = p.x[index(c.b)];
      if (periodic) {
        const PairNearA near_a = pair_near_a(*cell, xa, xb, point);
        point = near_a.point;
        xb = near_a.xb;
      }
      if (on_segment(xa, xb, point)) {
        add_branch(s, xa, xb, force, true);
      } else {
        add_branch(s, xa, point, force);
        add_branch(s, xb, point, -force);
      }
    } else {
      if (periodic) point = xa + dem::minimum_image(*cell, point - xa);
      add_branch(s, xa, point, force);
      s.wall_point.push_back(point);
      s.wall_force.push_back(force);
    }
  }
  return s;
}

bool point_near(const Vec3& x, const dem::Box& b, double range) {
  for (int d = 0; d < 3; ++d)
    if (x[d] < b.lo[d] - range || x[d] > b.hi[d] + range) return false;
  return true;
}

bool segment_near(const Vec3& a, const Vec3& c, const dem::Box& b, double range) {
  for (int d = 0; d < 3; ++d)
    if (std::max(a[d], c[d]) < b.lo[d] - range || std::min(a[d], c[d]) > b.hi[d] + range) return false;
  return true;
}

namespace {
Vec3 moved(const Vec3& x, const Vec3* shift) { return shift ? Vec3(x + *shift) : x; }
}  // namespace

void append_grain(GrainState& out, const GrainState& s, std::size_t i, const Vec3* shift) {
  out.id.push_back(s.id[i]);
  out.x.push_back(moved(s.x[i], shift));
  out.v.push_back(s.v[i]);
  out.acceleration.push_back(s.acceleration[i]);
  if (s.has_displacement()) out.displacement.push_back(s.displacement[i]);
  out.mass.push_back(s.mass[i]);
  out.volume.push_back(s.volume[i]);
}

void append_branch(GrainState& out, const GrainState& s, std::size_t k, const Vec3* shift) {
  out.branch_from.push_back(moved(s.branch_from[k], shift));
  out.branch_to.push_back(moved(s.branch_to[k], shift));
  out.branch_force.push_back(s.branch_force[k]);
  out.ends_at_grain.push_back(s.ends_at_grain[k]);
}

void append_wall_contact(GrainState& out, const GrainState& s, std::size_t k, const Vec3* shift) {
  out.wall_point.push_back(moved(s.wall_point[k], shift));
  out.wall_force.push_back(s.wall_force[k]);
}

GrainState part_near(const GrainState& s, const dem::Box& box, double range) {
  GrainState out;
  out.time = s.time;
  out.gravity = s.gravity;
  out.longest_branch = s.longest_branch;
  out.with_displacement = s.with_displacement;
  out.cell = s.cell;
  for (std::size_t i = 0; i < s.grains(); ++i)
    if (point_near(s.x[i], box, range)) append_grain(out, s, i);
  for (std::size_t k = 0; k < s.branches(); ++k)
    if (segment_near(s.branch_from[k], s.branch_to[k], box, range)) append_branch(out, s, k);
  for (std::size_t k = 0; k < s.wall_contacts(); ++k)
    if (point_near(s.wall_point[k], box, range)) append_wall_contact(out, s, k);
  return out;
}

}  // namespace upgrain::upscale::cg
