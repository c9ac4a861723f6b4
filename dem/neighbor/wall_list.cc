#include "dem/neighbor/wall_list.h"

#include <unordered_map>

namespace upgrain::dem {

void WallNeighborList::rebuild(const ParticleStore& p, const std::vector<PlaneWall>& walls) {
  lists_.resize(walls.size());
  std::unordered_map<GlobalId, TangentialSpring> active;
  std::unordered_map<GlobalId, double> radii;
  std::unordered_map<GlobalId, RollingSpring> rolling;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    Entries& e = lists_[w];
    active.clear();
    radii.clear();
    rolling.clear();
    for (std::size_t k = 0; k < e.spring.size(); ++k)
      if (e.spring[k].stiffness != 0.0) active.emplace(e.id[k], e.spring[k]);
    for (std::size_t k = 0; k < e.r_star.size(); ++k)
      if (e.r_star[k] != 0.0) radii.emplace(e.id[k], e.r_star[k]);
    for (std::size_t k = 0; k < e.rolling.size(); ++k)
      if (e.rolling[k].stiffness != 0.0) rolling.emplace(e.id[k], e.rolling[k]);
    e.particle.clear();
    e.id.clear();
    e.spring.clear();
    e.r_star.clear();
    e.rolling.clear();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (walls[w].distance(p.x[i]) >= p.radius[i] + skin_) continue;
      e.particle.push_back(static_cast<int>(i));
      e.id.push_back(p.id[i]);
      if (with_history_) {
        const auto it = active.find(p.id[i]);
        e.spring.push_back(it == active.end() ? TangentialSpring{} : it->second);
      }
      if (with_radii_) {
        const auto it = radii.find(p.id[i]);
        e.r_star.push_back(it == radii.end() ? 0.0 : it->second);
      }
      if (with_rolling_) {
        const auto it = rolling.find(p.id[i]);
        e.rolling.push_back(it == rolling.end() ? RollingSpring{} : it->second);
      }
    }
  }
}

}  // namespace upgrain::dem
