#include "coupling/studies/accuracy/bed_measures.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace upgrain::coupling {

const char* const kMeasureNames[kMeasures] = {"bed_height",   "solid_fraction", "contacts_per_particle",
                                              "floor_share",  "szz_levels",     "lateral_ratio",
                                              "balance_error"};

BedMeasures measure(const RunResult& r, long particles, double gravity) {
  BedMeasures m;
  m.height = r.bed.surface_height;
  m.solid_fraction = r.bed.solid_fraction;
  m.contacts_per_particle =
      2.0 * static_cast<double>(r.diagnostics.particle_contacts) / static_cast<double>(particles);
  for (std::size_t w = 0; w < r.wall_names.size(); ++w)
    if (r.wall_names[w] == "floor" && r.total_mass > 0.0 && gravity > 0.0)
      m.floor_share = r.wall_forces[w].z() / (r.total_mass * gravity);
  m.balance_error = r.energy_balance_error;
  m.lateral_ratio = std::numeric_limits<double>::quiet_NaN();
  if (!r.final_stress) return m;
  const dem::RegularGrid& g = r.final_grid;
  const std::vector<dem::Mat3>& s = (*r.final_stress)[dem::StressFormula::bagi];
  if (s.empty()) return m;
  const int per_level = g.n[0] * g.n[1];
  double ratio = 0.0;
  int cells = 0;
  for (int k = 0; k < g.n[2]; ++k) {
    double sum = 0.0;
    int n = 0;
    for (int c = k * per_level; c < (k + 1) * per_level; ++c) {
      if (r.final_stress->particles[c] == 0) continue;
      sum += s[c](2, 2);
      ++n;
      if (s[c](2, 2) != 0.0) {
        ratio += 0.5 * (s[c](0, 0) + s[c](1, 1)) / s[c](2, 2);
        ++cells;
      }
    }
    m.szz_levels.push_back(n > 0 ? sum / n : 0.0);
  }
  m.lateral_ratio = cells > 0 ? ratio / cells : std::numeric_limits<double>::quiet_NaN();
  return m;
}

std::vector<double> values(const BedMeasures& m) {
  double szz = 0.0;  // the level of largest magnitude: the one a reader quotes
  for (double v : m.szz_levels) szz = std::abs(v) > std::abs(szz) ? v : szz;
  return {m.height,
          m.solid_fraction,
          m.contacts_per_particle,
          m.floor_share,
          m.szz_levels.empty() ? std::numeric_limits<double>::quiet_NaN() : szz,
          m.lateral_ratio,
          m.balance_error};
}

std::vector<double> changes(const BedMeasures& a, const BedMeasures& b) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto relative = [&](double x, double y) { return std::abs(y - x) / std::max(std::abs(x), 1e-300); };
  std::vector<double> out = {relative(a.height, b.height),
                             relative(a.solid_fraction, b.solid_fraction),
                             relative(a.contacts_per_particle, b.contacts_per_particle),
                             relative(a.floor_share, b.floor_share),
                             nan,
                             relative(a.lateral_ratio, b.lateral_ratio),
                             std::abs(b.balance_error - a.balance_error)};
  if (!a.szz_levels.empty() && a.szz_levels.size() == b.szz_levels.size()) {
    double change = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < a.szz_levels.size(); ++k) {
      change = std::max(change, std::abs(b.szz_levels[k] - a.szz_levels[k]));
      scale = std::max(scale, std::abs(a.szz_levels[k]));
    }
    out[4] = change / std::max(scale, 1e-300);
  }
  return out;
}

}  // namespace upgrain::coupling
