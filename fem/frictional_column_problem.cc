// Input checks of the frictional column and its cone: plain C++, outside the deal.II
// translation unit.
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fem/frictional_column.h"

namespace upgrain::fem {

namespace {

void require(bool ok, const std::string& name, double value, const char* what) {
  if (ok) return;
  std::ostringstream msg;
  msg << "FrictionalColumnProblem." << name << " = " << value << ": " << what;
  throw std::invalid_argument(msg.str());
}

bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

void validate(const FrictionalColumnProblem& p) {
  validate(p.column);
  if (p.material == ColumnMaterial::drucker_prager) {
    const MohrCoulombStrength& s = p.strength;
    require(std::isfinite(s.friction_angle_deg) && s.friction_angle_deg > 0.0 && s.friction_angle_deg < 90.0,
            "strength.friction_angle_deg", s.friction_angle_deg, "must lie in (0, 90) degrees");
    require(std::isfinite(s.dilatancy_angle_deg) && s.dilatancy_angle_deg >= 0.0 &&
                s.dilatancy_angle_deg <= s.friction_angle_deg,
            "strength.dilatancy_angle_deg", s.dilatancy_angle_deg,
            "must lie in [0, friction_angle_deg] (a dilatancy above the friction angle is not admissible)");
    require(finite_non_negative(s.cohesion), "strength.cohesion", s.cohesion, "must be >= 0 and finite");
  }
  const char* side_names[4] = {"walls.side[0]", "walls.side[1]", "walls.side[2]", "walls.side[3]"};
  for (int w = 0; w < 4; ++w)
    require(finite_non_negative(p.walls.side[w]), side_names[w], p.walls.side[w], "must be >= 0 and finite");
  require(finite_non_negative(p.walls.floor), "walls.floor", p.walls.floor, "must be >= 0 and finite");
  require(std::isfinite(p.walls.penalty_factor) && p.walls.penalty_factor > 0.0, "walls.penalty_factor",
          p.walls.penalty_factor, "must be positive and finite");
  const ColumnLoading& l = p.loading;
  require(l.load_steps >= 1 && l.load_steps <= 10000, "loading.load_steps", l.load_steps,
          "must lie in [1, 10000]");
  const char* displacement_names[2] = {"loading.wall_displacement[0]", "loading.wall_displacement[1]"};
  for (int d = 0; d < 2; ++d)
    require(finite_non_negative(l.wall_displacement[d]), displacement_names[d], l.wall_displacement[d],
            "must be >= 0 (outwards) and finite");
  const bool moves = l.wall_displacement[0] > 0.0 || l.wall_displacement[1] > 0.0;
  require(!moves || (l.relaxation_steps >= 1 && l.relaxation_steps <= 10000), "loading.relaxation_steps",
          l.relaxation_steps, "must lie in [1, 10000] when a wall moves");
  require(std::isfinite(p.newton.tolerance) && p.newton.tolerance > 0.0 && p.newton.tolerance < 1.0,
          "newton.tolerance", p.newton.tolerance, "must lie in (0, 1)");
  require(p.newton.max_iterations >= 1 && p.newton.max_iterations <= 1000, "newton.max_iterations",
          p.newton.max_iterations, "must lie in [1, 1000]");
}

DruckerPrager drucker_prager_cone(const MohrCoulombStrength& s) {
  constexpr double degree = std::numbers::pi / 180.0;
  return match_mohr_coulomb(s.friction_angle_deg * degree, s.dilatancy_angle_deg * degree, s.cohesion,
                            s.matching);
}

}  // namespace upgrain::fem
