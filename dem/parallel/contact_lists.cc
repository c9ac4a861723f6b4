#include "dem/parallel/contact_lists.h"

#include <algorithm>

namespace upgrain::dem {

namespace {

TangentialSpring find_spring(const std::vector<SpringRecord>& history, GlobalId a, GlobalId b) {
  SpringRecord key{a, b, {0, 0, 0}, 0.0};
  const auto it = std::lower_bound(history.begin(), history.end(), key);
  if (it == history.end() || !it->same_key(key)) return TangentialSpring{};
  return TangentialSpring{get(it->force), it->stiffness};
}

ShapedContactMemory find_memory(const std::vector<MemoryRecord>& history, GlobalId a, GlobalId b) {
  MemoryRecord key{a, b, {0, 0, 0}, 0.0};
  const auto it = std::lower_bound(history.begin(), history.end(), key);
  if (it == history.end() || !it->same_key(key)) return ShapedContactMemory{};
  return ShapedContactMemory{get(it->normal), it->r_star};
}

}  // namespace

void ContactLists::build(const ParticleStore& p, int n_owned, double max_radius, double skin,
                         const std::vector<PlaneWall>& walls, const std::vector<SpringRecord>& history,
                         const std::vector<MemoryRecord>* memory_history) {
  const int n = static_cast<int>(p.size());
  lo.clear();
  hi.clear();
  Vec3 box_lo = Vec3::Zero(), box_hi = Vec3::Zero();
  if (n > 0) {
    box_lo = box_hi = p.x[0];
    for (int i = 1; i < n; ++i) {
      box_lo = box_lo.cwiseMin(p.x[i]);
      box_hi = box_hi.cwiseMax(p.x[i]);
    }
  }
  grid_ = CellGrid(box_lo, box_hi, 2.0 * max_radius + skin, 4L * n + 64);
  grid_.bin(p.x);
  const std::vector<int>& start = grid_.cell_start();
  const std::vector<int>& order = grid_.order();
  const auto& dims = grid_.dims();

  // 1. Pair slots: an owned-owned pair from its lower-id side, an owned-ghost pair from
  //    the owned side; ghost-ghost pairs are left to their owners.
  for (int i = 0; i < n_owned; ++i) {
    const Vec3 xi = p.x[i];
    const double ri = p.radius[i] + skin;
    const GlobalId gi = p.id[i];
    const auto c = grid_.cell_coords(xi);
    for (int z = std::max(c[2] - 1, 0); z <= std::min(c[2] + 1, dims[2] - 1); ++z)
      for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims[1] - 1); ++y)
        for (int x = std::max(c[0] - 1, 0); x <= std::min(c[0] + 1, dims[0] - 1); ++x) {
          const int cell = grid_.flat(x, y, z);
          for (int s = start[cell]; s < start[cell + 1]; ++s) {
            const int j = order[s];
            if (j == i || (j < n_owned && p.id[j] < gi)) continue;
            const double cut = ri + p.radius[j];
            if ((p.x[j] - xi).squaredNorm() >= cut * cut) continue;
            const bool i_lower = gi < p.id[j];
            lo.push_back(i_lower ? i : j);
            hi.push_back(i_lower ? j : i);
          }
        }
  }
  const std::size_t m = lo.size();

  // 2. Rows of the owned particles, sorted by the partner's global id.
  row_start.assign(static_cast<std::size_t>(n_owned) + 1, 0);
  for (std::size_t k = 0; k < m; ++k) {
    if (lo[k] < n_owned) ++row_start[lo[k] + 1];
    if (hi[k] < n_owned) ++row_start[hi[k] + 1];
  }
  for (int i = 0; i < n_owned; ++i) row_start[i + 1] += row_start[i];
  row.resize(static_cast<std::size_t>(row_start[n_owned]));
  std::vector<int> fill(row_start.begin(), row_start.end() - 1);
  for (std::size_t k = 0; k < m; ++k) {
    const int e = static_cast<int>(2 * k);
    if (lo[k] < n_owned) row[fill[lo[k]]++] = e;
    if (hi[k] < n_owned) row[fill[hi[k]]++] = e + 1;
  }
  auto partner_id = [&](int e) { return p.id[(e & 1) ? lo[e >> 1] : hi[e >> 1]]; };
  for (int i = 0; i < n_owned; ++i)
    std::sort(row.begin() + row_start[i], row.begin() + row_start[i + 1],
              [&](int a, int b) { return partner_id(a) < partner_id(b); });

  // 3. Springs of the pairs, from the history keyed by global ids.
  spring.assign(m, TangentialSpring{});
  if (!history.empty()) {
    for (std::size_t k = 0; k < m; ++k) spring[k] = find_spring(history, p.id[lo[k]], p.id[hi[k]]);
  }
  memory.clear();
  if (memory_history != nullptr) {
    memory.resize(m);
    for (std::size_t k = 0; k < m; ++k) memory[k] = find_memory(*memory_history, p.id[lo[k]], p.id[hi[k]]);
  }
  force.resize(m);
  torque_lo.resize(m);
  torque_hi.resize(m);
  touching.assign(m, 0);
  elastic_normal.assign(m, 0.0);
  elastic_tangential.assign(m, 0.0);
  damping_on_lo.assign(m, Vec3::Zero());
  damping_torque_lo.assign(memory_history != nullptr ? m : 0, Vec3::Zero());
  damping_torque_hi.assign(memory_history != nullptr ? m : 0, Vec3::Zero());

  // 4. Wall contacts of the owned particles, by particle then wall.
  wall.clear();
  for (int i = 0; i < n_owned; ++i) {
    for (std::size_t w = 0; w < walls.size(); ++w) {
      if (walls[w].distance(p.x[i]) >= p.radius[i] + skin) continue;
      const TangentialSpring s =
          history.empty() ? TangentialSpring{} : find_spring(history, p.id[i], -1 - static_cast<GlobalId>(w));
      wall.push_back({i, static_cast<int>(w), s});
    }
  }
  wall_force_on_particle.assign(wall.size(), Vec3::Zero());
  wall_r_star.clear();
  if (memory_history != nullptr) {
    wall_r_star.resize(wall.size());
    for (std::size_t e = 0; e < wall.size(); ++e)
      wall_r_star[e] =
          find_memory(*memory_history, p.id[wall[e].particle], -1 - static_cast<GlobalId>(wall[e].wall))
              .r_star;
  }
}

void ContactLists::collect_springs(const ParticleStore& p, std::vector<SpringRecord>& out) const {
  for (std::size_t k = 0; k < spring.size(); ++k) {
    const TangentialSpring& s = spring[k];
    if (s.stiffness == 0.0) continue;
    SpringRecord r{p.id[lo[k]], p.id[hi[k]], {0, 0, 0}, s.stiffness};
    put(r.force, s.force);
    out.push_back(r);
  }
  for (const WallContact& c : wall) {
    if (c.spring.stiffness == 0.0) continue;
    SpringRecord r{p.id[c.particle], -1 - static_cast<GlobalId>(c.wall), {0, 0, 0}, c.spring.stiffness};
    put(r.force, c.spring.force);
    out.push_back(r);
  }
}

void ContactLists::collect_memory(const ParticleStore& p, std::vector<MemoryRecord>& out) const {
  for (std::size_t k = 0; k < memory.size(); ++k) {
    const ShapedContactMemory& m = memory[k];
    if (m.empty()) continue;
    MemoryRecord r{p.id[lo[k]], p.id[hi[k]], {0, 0, 0}, m.r_star};
    put(r.normal, m.normal);
    out.push_back(r);
  }
  for (std::size_t e = 0; e < wall_r_star.size(); ++e) {
    if (wall_r_star[e] == 0.0) continue;
    out.push_back(
        {p.id[wall[e].particle], -1 - static_cast<GlobalId>(wall[e].wall), {0, 0, 0}, wall_r_star[e]});
  }
}

}  // namespace upgrain::dem
