#pragma once
// Dynamic load balance of the Cartesian blocks (docs/parallel.md, "Load balance"): the cut
// planes of each axis move to the quantiles of the cost distribution along that axis, so
// that every slab of blocks carries the same share of the cost. This is the rule of the
// `shift` style of LAMMPS's `balance` and `fix balance` commands
// (https://docs.lammps.org/balance.html), which moves the cuts of a tensor grid so that
// the slabs along each dimension hold equal counts; LAMMPS finds each cut by iterated
// bisection, here it is read off a reduced histogram in one pass. It is the per-axis cut of
// recursive coordinate bisection (Berger & Bokhari 1987, IEEE Trans. Comput. C-36:570)
// restricted to keep the px x py x pz grid, so the three-stage ghost exchange stays valid
// (every block's face neighbours share its planes).
//
// The kernels are plain functions over integer histograms: every rank computes the same
// cuts from the same reduced histogram (an integer MPI_SUM is exact and independent of the
// reduction order), so the planes are bit for bit identical on every rank.
#include <vector>

namespace upgrain::dem {

// What the balance equalises. `particles`: one per owned particle. `pair_slots`: one per
// owned particle plus one per entry of its neighbour-list row (its pair slots, ghost
// partners included), i.e. the work of the force loop and of the segmented force sum.
enum class BalanceCost { particles, pair_slots };

// Bins of a cost histogram along one axis. 4096 bins over the box: the planes are placed to
// 1/4096 of the box (with linear interpolation inside a bin, finer), and a histogram of
// three axes reduces in one 96 kB message at a rebalance.
constexpr int kBalanceBins = 4096;

// The bin of coordinate x among `bins` equal bins over [lo, hi]; points outside (the
// outer blocks are open) fall into the end bins.
int balance_bin(double x, double lo, double hi, int bins);

// The parts - 1 interior cut positions over [lo, hi] that split the cost of `histogram`
// (`bins` equal bins over [lo, hi]) into `parts` equal shares: cut k sits where the
// cumulative cost reaches k / parts of the total, interpolated linearly inside its bin
// (cost assumed uniform within a bin). Ascending; empty when parts < 2; equally spaced
// when the histogram is empty.
std::vector<double> quantile_cuts(const long* histogram, int bins, double lo, double hi, int parts);

// Moves `cuts` (ascending, inside [lo, hi]) the least, in a forward then a backward pass,
// so that every interior block — between two consecutive cuts — is at least `min_block`
// thick, and every cut stays inside [lo, hi]. The two outer blocks are open outwards and
// need no clamp: a particle of the first block lies below cut 1, more than `min_block`
// from cut 2, so it is never a ghost of the third block. Requires (cuts.size() - 1)
// min_block <= hi - lo, which a decomposition that passed its thin-block check satisfies
// (blocks * min_block <= hi - lo). After the call, cuts[k + 1] - cuts[k] >= min_block
// holds exactly in floating point.
void clamp_cuts(std::vector<double>& cuts, double lo, double hi, double min_block);

// max/mean of per-rank costs (1 for a perfect balance, and when the total is zero).
inline double imbalance_ratio(long max_cost, long total_cost, int ranks) {
  return total_cost > 0 ? static_cast<double>(max_cost) * ranks / static_cast<double>(total_cost) : 1.0;
}

}  // namespace upgrain::dem
