#include "dem/core/contact_history.h"

#include <algorithm>

namespace upgrain::dem {

namespace {

void put3(double* out, const Vec3& v) { out[0] = v[0], out[1] = v[1], out[2] = v[2]; }
Vec3 get3(const double* in) { return Vec3(in[0], in[1], in[2]); }

// The record of one contact, oriented from the contact's body i (id_i).
ContactHistoryRecord make_record(GlobalId id_i, GlobalId id_j, const TangentialSpring& s,
                                 const RollingSpring& r, const ShapedContactMemory& m, bool keep_gap_budget) {
  ContactHistoryRecord c;
  c.a = id_i;
  c.b = id_j;
  put3(c.tangential_force, s.force);
  c.tangential_stiffness = s.stiffness;
  put3(c.rolling_torque, r.torque);
  c.rolling_stiffness = r.stiffness;
  c.twisting_torque = r.twist;
  c.twisting_stiffness = r.twist_stiffness;
  put3(c.normal, m.normal);
  c.r_star = m.r_star;
  c.gap_budget = keep_gap_budget ? m.gap_budget : 0.0;
  return c;
}

RollingSpring rolling_spring(const ContactHistoryRecord& c) {
  return {get3(c.rolling_torque), c.rolling_stiffness, c.twisting_torque, c.twisting_stiffness};
}

const ContactHistoryRecord* find(const std::vector<ContactHistoryRecord>& records, GlobalId a, GlobalId b) {
  ContactHistoryRecord key;
  key.a = a;
  key.b = b;
  const auto it = std::lower_bound(records.begin(), records.end(), key);
  return it == records.end() || !it->same_key(key) ? nullptr : &*it;
}

}  // namespace

void ContactHistory::collect(const PairList& pairs, const WallList& walls, const std::vector<GlobalId>& id,
                             bool keep_gap_budget, std::vector<ContactHistoryRecord>& out) const {
  const TangentialSpring no_spring;
  const RollingSpring no_rolling;
  const ShapedContactMemory no_memory;
  for (std::size_t r = 0; r < pairs.num_rows(); ++r) {
    const int i = pairs.row_particle[r];
    for (int k = pairs.row_start[r]; k < pairs.row_start[r + 1]; ++k) {
      const TangentialSpring& s = kinds_.tangential ? pair_spring[k] : no_spring;
      const RollingSpring& ro = kinds_.rolling ? pair_rolling[k] : no_rolling;
      const ShapedContactMemory& m = kinds_.shapes ? pair_memory[k] : no_memory;
      if (s.stiffness == 0.0 && ro.stiffness == 0.0 && ro.twist_stiffness == 0.0 && m.empty())
        continue;  // nothing to carry
      const GlobalId a = id[i];
      const GlobalId b = id[pairs.partner[k]];
      out.push_back(a < b ? make_record(a, b, s, ro, m, keep_gap_budget)
                          : make_record(b, a, s.reversed(), ro.reversed(), m.reversed(), keep_gap_budget));
    }
  }
  for (std::size_t e = 0; e < walls.size(); ++e) {
    const TangentialSpring& s = kinds_.wall_tangential ? wall_spring[e] : no_spring;
    const RollingSpring& ro = kinds_.rolling ? wall_rolling[e] : no_rolling;
    ShapedContactMemory m;
    if (kinds_.shapes) m.r_star = wall_r_star[e];
    if (s.stiffness == 0.0 && ro.stiffness == 0.0 && ro.twist_stiffness == 0.0 && m.r_star == 0.0) continue;
    out.push_back(make_record(id[walls.particle[e]], wall_key(walls.wall[e]), s, ro, m, false));
  }
}

void ContactHistory::restore(const PairList& pairs, const WallList& walls, const std::vector<GlobalId>& id,
                             const std::vector<ContactHistoryRecord>& records) {
  const std::size_t m = pairs.num_pairs();
  pair_spring.assign(kinds_.tangential ? m : 0, TangentialSpring{});
  pair_rolling.assign(kinds_.rolling ? m : 0, RollingSpring{});
  pair_memory.assign(kinds_.shapes ? m : 0, ShapedContactMemory{});
  wall_spring.assign(kinds_.wall_tangential ? walls.size() : 0, TangentialSpring{});
  wall_rolling.assign(kinds_.rolling ? walls.size() : 0, RollingSpring{});
  wall_r_star.assign(kinds_.shapes ? walls.size() : 0, 0.0);
  if (records.empty()) return;
  for (std::size_t r = 0; r < pairs.num_rows(); ++r) {
    const GlobalId a = id[pairs.row_particle[r]];
    for (int k = pairs.row_start[r]; k < pairs.row_start[r + 1]; ++k) {
      const GlobalId b = id[pairs.partner[k]];
      const ContactHistoryRecord* c = a < b ? find(records, a, b) : find(records, b, a);
      if (c == nullptr) continue;
      const TangentialSpring s{get3(c->tangential_force), c->tangential_stiffness};
      const RollingSpring ro = rolling_spring(*c);
      const ShapedContactMemory mem{get3(c->normal), c->r_star, c->gap_budget};
      if (kinds_.tangential) pair_spring[k] = a < b ? s : s.reversed();
      if (kinds_.rolling) pair_rolling[k] = a < b ? ro : ro.reversed();
      if (kinds_.shapes) pair_memory[k] = a < b ? mem : mem.reversed();
    }
  }
  for (std::size_t e = 0; e < walls.size(); ++e) {
    const ContactHistoryRecord* c = find(records, id[walls.particle[e]], wall_key(walls.wall[e]));
    if (c == nullptr) continue;
    if (kinds_.wall_tangential) wall_spring[e] = {get3(c->tangential_force), c->tangential_stiffness};
    if (kinds_.rolling) wall_rolling[e] = rolling_spring(*c);
    if (kinds_.shapes) wall_r_star[e] = c->r_star;
  }
}

void sort_unique(std::vector<ContactHistoryRecord>& records) {
  std::sort(records.begin(), records.end());
  records.erase(
      std::unique(records.begin(), records.end(),
                  [](const ContactHistoryRecord& x, const ContactHistoryRecord& y) { return x.same_key(y); }),
      records.end());
}

}  // namespace upgrain::dem
