#pragma once
// The side walls' shear against height (docs/study.md, "Wall shear against height"): per level
// of the stress grid, the mean upward traction the four side walls exert on the fill,
//   tau_k = (upward force of the side walls on the fill within level k) / (P dz),
// with P = 2 (Lx + Ly) the box's perimeter and dz the level's height (Pa; positive where the
// walls carry weight). Summed over the levels, tau_k P dz is the side walls' share of the weight
// times the weight. The DEM's from its side-wall contacts binned by their points' height, the
// frictional continua's from their wall tractions per level, Janssen's from his slab solution.
#include <algorithm>
#include <vector>

#include "coupling/run/run_result.h"
#include "fem/analytic/janssen.h"

namespace upgrain::coupling {

// The levels of a grid: `levels` of height `dz` from `z0`. A point below z0 or above the top
// belongs to the nearest level (contacts reach a grain's radius beyond its centre).
struct Levels {
  double z0 = 0.0;
  double dz = 1.0;
  int levels = 1;
  [[nodiscard]] int of(double z) const {
    return std::clamp(static_cast<int>((z - z0) / dz), 0, levels - 1);  // floor for z >= z0
  }
};

// The levels of a stress grid, and the box's perimeter P = 2 (Lx + Ly).
inline Levels grid_levels(const dem::RegularGrid& g) {
  return {g.lo.z(), (g.hi.z() - g.lo.z()) / g.n[2], g.n[2]};
}
inline double box_perimeter(const dem::SceneConfig& s) { return 2.0 * (s.container.lx + s.container.ly); }

// The DEM's: each side-wall contact's vertical force on its grain, in the level of its point.
inline std::vector<double> dem_wall_shear(const std::vector<SideWallContact>& contacts, const Levels& l,
                                          double perimeter) {
  std::vector<double> tau(static_cast<std::size_t>(l.levels), 0.0);
  for (const SideWallContact& c : contacts) tau[static_cast<std::size_t>(l.of(c.z))] += c.force_on_grain.z();
  for (double& t : tau) t /= perimeter * l.dz;
  return tau;
}

// A continuum's: its side walls' upward force on the fill per level (N), over P dz.
inline std::vector<double> wall_shear_of_forces(const std::vector<double>& force_by_level, const Levels& l,
                                                double perimeter) {
  std::vector<double> tau(force_by_level);
  for (double& t : tau) t /= perimeter * l.dz;
  return tau;
}

// Janssen's: on wall i, tau_i = mu_i K p(z) (Janssen 1895); averaged over the perimeter and
// over the level, (sum_i mu_i L_i) K mean(p) / P.
inline std::vector<double> janssen_wall_shear(const fem::JanssenColumn& j, const Levels& l,
                                              double perimeter) {
  std::vector<double> tau(static_cast<std::size_t>(l.levels));
  for (int k = 0; k < l.levels; ++k)
    tau[static_cast<std::size_t>(k)] = -j.friction_perimeter * j.lateral_ratio *
                                       j.mean_vertical_stress(l.z0 + k * l.dz, l.z0 + (k + 1) * l.dz) /
                                       perimeter;
  return tau;
}

}  // namespace upgrain::coupling
