#include "dem/parallel/load_balance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace upgrain::dem {

int balance_bin(double x, double lo, double hi, int bins) {
  const double s = (x - lo) / (hi - lo) * bins;
  // `!(s >= 0)` also sends NaN to the first bin; the caller has checked finiteness.
  if (!(s >= 0.0)) return 0;
  if (s >= bins) return bins - 1;
  return static_cast<int>(s);
}

std::vector<double> quantile_cuts(const long* histogram, int bins, double lo, double hi, int parts) {
  std::vector<double> cuts;
  if (parts < 2) return cuts;
  cuts.reserve(static_cast<std::size_t>(parts - 1));
  long total = 0;
  for (int b = 0; b < bins; ++b) total += histogram[b];
  const double width = (hi - lo) / bins;
  if (total == 0) {
    for (int k = 1; k < parts; ++k) cuts.push_back(lo + k * (hi - lo) / parts);
    return cuts;
  }
  // One sweep: cumulative cost `below` before bin b; cut k is due when it reaches
  // k total / parts. Integer comparisons (k total <= parts (below + h)) decide the bin,
  // so the bin of each cut does not depend on rounding.
  long below = 0;
  int b = 0;
  for (int k = 1; k < parts; ++k) {
    const long target_times_parts = static_cast<long>(k) * total;
    while (b < bins && static_cast<long>(parts) * (below + histogram[b]) < target_times_parts) {
      below += histogram[b];
      ++b;
    }
    if (b == bins) {  // unreachable: the last bin reaches the total
      cuts.push_back(hi);
      continue;
    }
    // Cost uniform inside the bin: the fraction of bin b below the cut.
    const double inside = static_cast<double>(target_times_parts - static_cast<long>(parts) * below) /
                          (static_cast<double>(parts) * static_cast<double>(histogram[b]));
    cuts.push_back(std::min(hi, lo + (b + inside) * width));
  }
  // Rounding cannot reorder them (b and `inside` grow with k), but keep the invariant explicit.
  for (std::size_t k = 1; k < cuts.size(); ++k) cuts[k] = std::max(cuts[k], cuts[k - 1]);
  return cuts;
}

void clamp_cuts(std::vector<double>& cuts, double lo, double hi, double min_block) {
  const std::size_t n = cuts.size();
  if (n == 0) return;
  // Each pass changes a cut only where the rule fails, so cuts that satisfy it stay put
  // (and the clamp is idempotent).
  // Forward: each cut at least min_block above the previous one (and inside the box).
  cuts[0] = std::clamp(cuts[0], lo, hi);
  for (std::size_t k = 1; k < n; ++k)
    if (cuts[k] - cuts[k - 1] < min_block) cuts[k] = cuts[k - 1] + min_block;
  // Backward: pull the cuts that the forward pass pushed past hi back, keeping the gaps.
  // (c - m) can round so that the gap falls an ulp short of m: step c down until the gap
  // holds in floating point, so Decomposition::set_cuts's exact check accepts it.
  cuts[n - 1] = std::min(cuts[n - 1], hi);
  const double down = -std::numeric_limits<double>::infinity();
  for (std::size_t k = n - 1; k-- > 0;) {
    if (cuts[k + 1] - cuts[k] >= min_block) continue;
    cuts[k] = cuts[k + 1] - min_block;
    while (cuts[k + 1] - cuts[k] < min_block) cuts[k] = std::nextafter(cuts[k], down);
  }
}

}  // namespace upgrain::dem
