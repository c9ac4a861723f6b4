#include "dem/engine/particle_sums.h"

#include <algorithm>
#include <cmath>

#include "dem/parallel/exchange.h"
#include "dem/parallel/fixed_point_sum.h"

namespace upgrain::dem {

ParticleSums::ParticleSums(Summation summation, int quantities, int n_owned)
    : deterministic_(summation == Summation::deterministic) {
  if (deterministic_)
    terms_.assign(static_cast<std::size_t>(quantities),
                  std::vector<double>(static_cast<std::size_t>(n_owned), 0.0));
  else
    running_.assign(static_cast<std::size_t>(quantities), 0.0);
}

std::vector<double> ParticleSums::totals(MPI_Comm comm) const {
  if (!deterministic_) {
    std::vector<double> sums = running_;
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM, comm);
    return sums;
  }
  // The bound of each quantity is the exact global maximum of its |terms|.
  std::vector<double> bound(terms_.size(), 0.0);
  for (std::size_t q = 0; q < terms_.size(); ++q)
    for (double t : terms_[q]) bound[q] = std::max(bound[q], std::abs(t));
  MPI_Allreduce(MPI_IN_PLACE, bound.data(), static_cast<int>(bound.size()), MPI_DOUBLE, MPI_MAX, comm);
  FixedPointSums s(bound);
  for (std::size_t q = 0; q < terms_.size(); ++q)
    for (double t : terms_[q]) s.add(static_cast<int>(q), t);
  return global_sums(s, comm);
}

}  // namespace upgrain::dem
