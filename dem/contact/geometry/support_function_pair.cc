#include "dem/contact/geometry/support_function_pair.h"

namespace upgrain::dem {

void shaped_pair_geometries(const GrainPoses& poses, std::vector<ShapedPair>& pairs,
                            const ContactSolverSettings& settings, ContactSolverStats& stats) {
  // A pair touching at the last step (a held radius and a normal) is solved warm without
  // curvatures: two such pairs go through the two lanes together; the others one at a time.
  ShapedPair* waiting = nullptr;
  auto alone = [&](ShapedPair& s) {
    PairContact c;
    const ShapedContactMemory& m = *s.memory;
    const bool touching =
        posed_contact(poses[s.i], poses[s.j], m.normal != Vec3::Zero() ? &m.normal : nullptr, m.r_star == 0.0,
                      settings, stats, c);
    finish_pair(poses, c, touching, s);
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
    WarmPairSolve wa{&poses[a.i], &poses[a.j], a.memory->normal, {}, false};
    WarmPairSolve ws{&poses[s.i], &poses[s.j], s.memory->normal, {}, false};
    posed_contacts_two(wa, ws, settings, stats);
    finish_pair(poses, wa.out, wa.touching, a);
    finish_pair(poses, ws.out, ws.touching, s);
  }
  if (waiting) alone(*waiting);
}

}  // namespace upgrain::dem
