#pragma once
// Global sums of per-particle terms over the owned particles of every rank, in the order the
// summation asks for (summation.h):
//  - fast: running sums in local order, then an MPI_SUM over the ranks;
//  - deterministic: each particle's terms kept apart, then summed by fixed-point limbs
//    (dem/parallel/fixed_point_sum.h), the same bits on any partition of the particles.
// Used where a global sum steers the particle states (FIRE's power and norms,
// dem/engine/relaxation.h).
#include <mpi.h>

#include <vector>

#include "dem/engine/summation.h"

namespace upgrain::dem {

class ParticleSums {
 public:
  ParticleSums(Summation summation, int quantities, int n_owned);

  // Adds `term` to quantity q for owned particle i.
  void add(int q, int i, double term) {
    if (deterministic_)
      terms_[static_cast<std::size_t>(q)][static_cast<std::size_t>(i)] += term;
    else
      running_[static_cast<std::size_t>(q)] += term;
  }
  // Collective: every quantity's sum over every rank, the same on every rank.
  [[nodiscard]] std::vector<double> totals(MPI_Comm comm) const;

 private:
  bool deterministic_;
  std::vector<std::vector<double>> terms_;
  std::vector<double> running_;
};

}  // namespace upgrain::dem
