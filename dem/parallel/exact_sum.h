#pragma once
// Exact sums of doubles, whatever their number, order, magnitude and sign, and whatever the
// ranks they are divided among: a long accumulator over the whole exponent range of double
// (Kulisch and Miranker 1981; the "superaccumulator" of Collange, Defour, Graillat and Iakymchuk,
// Parallel Computing 49:83, 2015). Every double is an integer multiple of 2^-1074; its
// significand, shifted to its exponent, is added into 32-bit digits held in int64 words, which
// absorb 2^31 additions before a carry pass is needed. Integer additions are associative, so
// the digits summed over ranks (MPI_SUM of int64) are those of one rank adding every term: the
// value is the same bits on any rank count, and it can be written to a checkpoint and continued
// elsewhere.
//
// Used for the cumulative dissipation of the deterministic summation (dem/engine/simulation.h):
// each grain's share of a step is added once, so the energy columns of a run do not depend on
// how the grains are divided among ranks.
#include <mpi.h>

#include <array>
#include <bit>
#include <cstdint>
#include <span>

namespace upgrain::dem {

class ExactSum {
 public:
  // 2^-1074 .. 2^1024 in 32-bit digits, and two more for the carries of a sum.
  static constexpr int kDigits = 68;

  void add(double term) {
    if (term == 0.0) return;
    const auto bits = std::bit_cast<std::uint64_t>(term);
    const int biased = static_cast<int>((bits >> 52) & 0x7ff);
    std::uint64_t significand = bits & ((std::uint64_t{1} << 52) - 1);
    if (biased == 0x7ff) {  // inf or NaN: kept apart, the value is then NaN
      non_finite_ = 1;
      return;
    }
    if (biased != 0) significand |= std::uint64_t{1} << 52;
    if (significand == 0) return;
    // In units of 2^-1074, term = significand 2^(max(biased, 1) - 1).
    const int position = (biased == 0 ? 1 : biased) - 1;
    const int digit = position >> 5, shift = position & 31;
    // The shifted significand spans at most 53 + 31 bits: three digits.
    const std::uint64_t low = significand << shift;
    const std::uint64_t high = shift == 0 ? 0 : significand >> (64 - shift);
    const auto d0 = static_cast<std::int64_t>(low & 0xffffffffu);
    const auto d1 = static_cast<std::int64_t>(low >> 32);
    const auto d2 = static_cast<std::int64_t>(high);
    if (static_cast<std::int64_t>(bits) < 0) {
      digits_[digit] -= d0;
      digits_[digit + 1] -= d1;
      digits_[digit + 2] -= d2;
    } else {
      digits_[digit] += d0;
      digits_[digit + 1] += d1;
      digits_[digit + 2] += d2;
    }
    if (++pending_ == kCarryEvery) carry();
  }

  // The exact sum rounded to double (within one unit in the last place), a function of the
  // exact sum only. NaN if an infinite or NaN term was added.
  [[nodiscard]] double value() const;

  // The sum of every rank's terms, on every rank (collective).
  [[nodiscard]] ExactSum reduced(MPI_Comm comm) const;
  // Every accumulator of `sums` replaced by its sum over the ranks, in one message (collective).
  static void reduce(std::span<ExactSum> sums, MPI_Comm comm);
  // Adds another accumulator's terms.
  void add(const ExactSum& other);

  // The state, for a checkpoint: carried digits (each in [0, 2^32) but the top one, which
  // holds the sign) and the non-finite flag; and back.
  [[nodiscard]] std::array<std::int64_t, kDigits + 1> state() const;
  static ExactSum from_state(const std::array<std::int64_t, kDigits + 1>& s);

 private:
  static constexpr int kCarryEvery = 1 << 30;
  void carry();

  std::array<std::int64_t, kDigits> digits_{};
  std::int64_t non_finite_ = 0;
  int pending_ = 0;
};

}  // namespace upgrain::dem
