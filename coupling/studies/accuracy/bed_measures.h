#pragma once
// What a user reads off a bed (docs/accuracy.md): its height, solid fraction, contacts per
// particle, the share of its weight the floor carries, the Bagi sigma_zz of each level of the
// stress grid, the mean lateral ratio, and the energy-balance error; and how far two beds'
// measures are apart. A deposition is chaotic: two settings never give the same packing, so
// beds are compared by these, not grain by grain.
#include <string>
#include <vector>

#include "coupling/run/run_result.h"

namespace upgrain::coupling {

struct BedMeasures {
  double height = 0.0;          // m
  double solid_fraction = 0.0;  // of the core
  double contacts_per_particle = 0.0;
  double floor_share = 0.0;    // floor's normal force / the grains' weight
  double lateral_ratio = 0.0;  // mean over cells with grains of (s_xx + s_yy) / (2 s_zz), Bagi
  double balance_error = 0.0;  // (docs/integrator.md); NaN without energy tracking
  std::vector<double>
      szz_levels;  // Bagi sigma_zz averaged over each level of the grid (Pa); empty without it
};

// The measures of a finished run (rank 0): `particles`, `gravity` (m/s^2) and `mass` give the weight.
BedMeasures measure(const RunResult& r, long particles, double gravity);

// The measures by name, in a fixed order, and the change of each between two beds: relative to
// the reference's magnitude (sigma_zz: the largest level change over the largest level), the
// balance error absolutely (it is a ratio already). NaN where either bed lacks the measure.
inline constexpr int kMeasures = 7;
extern const char* const kMeasureNames[kMeasures];
std::vector<double> changes(const BedMeasures& reference, const BedMeasures& other);
std::vector<double> values(const BedMeasures& m);

}  // namespace upgrain::coupling
