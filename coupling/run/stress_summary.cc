#include "coupling/run/stress_summary.h"

#include <algorithm>

#include "dem/stress/asymmetry.h"

namespace upgrain::coupling {

StressSummary summarise_stress(const dem::GridStress& g, const dem::RegularGrid& grid, dem::StressFormula f) {
  StressSummary s;
  const std::vector<dem::Mat3>& sigma = g[f];
  // The scale: the largest stress of any formula written (a formula without contacts yet is
  // round-off everywhere, while the body-force formulas carry the grains' weight).
  double largest = 0.0;
  for (const std::vector<dem::Mat3>& formula : g.sigma)
    for (std::size_t c = 0; c < formula.size(); ++c)
      if (g.particles[c] > 0) largest = std::max(largest, formula[c].norm());
  int floor_cells = 0;
  for (int c = 0; c < grid.num_cells(); ++c) {
    if (g.particles[c] == 0) continue;
    if (c < grid.n[0] * grid.n[1]) {
      s.floor_szz += sigma[c](2, 2);
      ++floor_cells;
    }
    if (!(sigma[c].norm() > kNegligibleStress * largest)) {
      ++s.negligible_cells;
      continue;
    }
    ++s.rated_cells;
    s.max_rai = std::max(s.max_rai, dem::relative_asymmetry_index(sigma[c]));
  }
  if (floor_cells > 0) s.floor_szz /= floor_cells;
  return s;
}

}  // namespace upgrain::coupling
