#include "dem/engine/particle_sums.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "dem/parallel/exchange.h"
#include "dem/parallel/fixed_point_sum.h"

namespace upgrain::dem {

namespace {

// max |t| over the terms, in four independent lanes (a single running maximum waits on the
// latency of each comparison).
double max_abs(const std::vector<double>& terms) {
  constexpr std::size_t kLanes = 4;
  std::array<double, kLanes> m{};
  std::size_t i = 0;
  for (; i + kLanes <= terms.size(); i += kLanes)
    for (std::size_t lane = 0; lane < kLanes; ++lane) m[lane] = std::max(m[lane], std::abs(terms[i + lane]));
  for (; i < terms.size(); ++i) m[0] = std::max(m[0], std::abs(terms[i]));
  return std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
}

}  // namespace

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
  for (std::size_t q = 0; q < terms_.size(); ++q) bound[q] = max_abs(terms_[q]);
  MPI_Allreduce(MPI_IN_PLACE, bound.data(), static_cast<int>(bound.size()), MPI_DOUBLE, MPI_MAX, comm);
  FixedPointSums s(bound);
  for (std::size_t q = 0; q < terms_.size(); ++q) s.add_terms(static_cast<int>(q), terms_[q]);
  return global_sums(s, comm);
}

}  // namespace upgrain::dem
