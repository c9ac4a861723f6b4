#include "dem/contact/shaped_contact.h"

namespace upgrain::dem {

namespace {

// finish_pair() into a ShapedPair.
void finish(const GrainPoses& poses, ShapedPair& s, bool touching, const PairContact& c) {
  ContactKinematics kin;
  s.touching = finish_pair(poses, s.i, s.j, touching, c, *s.memory, kin, s.r_star);
  if (!s.touching) return;
  s.normal = kin.normal;
  s.overlap = kin.overlap;
  s.lever_i = kin.lever_i;
  s.lever_j = kin.lever_j;
}

}  // namespace

void shaped_pair_geometries(const GrainPoses& poses, std::vector<ShapedPair>& pairs,
                            ContactSolverStats& stats) {
  // A pair touching at the last step (a held radius and a normal) is solved warm without
  // curvatures: two such pairs go through the two lanes together; the others one at a time.
  ShapedPair* waiting = nullptr;
  auto alone = [&](ShapedPair& s) {
    PairContact c;
    const ShapedContactMemory& m = *s.memory;
    const bool touching = posed_contact(
        poses[s.i], poses[s.j], m.normal != Vec3::Zero() ? &m.normal : nullptr, m.r_star == 0.0, stats, c);
    finish(poses, s, touching, c);
  };
  for (ShapedPair& s : pairs) {
    if (still_apart(poses, s.i, s.j, *s.memory, stats)) {
      s.touching = false;
      continue;
    }
    const ShapedContactMemory& m = *s.memory;
    if (m.r_star == 0.0 || m.normal == Vec3::Zero()) {
      alone(s);
      continue;
    }
    if (!waiting) {
      waiting = &s;
      continue;
    }
    ShapedPair& a = *waiting;
    waiting = nullptr;
    PairContact ca, cb;
    bool ta = false, tb = false;
    posed_contacts_two(poses[a.i], poses[a.j], a.memory->normal, poses[s.i], poses[s.j], s.memory->normal,
                       stats, ca, cb, ta, tb);
    finish(poses, a, ta, ca);
    finish(poses, s, tb, cb);
  }
  if (waiting) alone(*waiting);
}

}  // namespace upgrain::dem
