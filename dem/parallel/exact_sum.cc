#include "dem/parallel/exact_sum.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace upgrain::dem {

void ExactSum::carry() {
  // Floor division by 2^32 (arithmetic shift): digits 0 .. kDigits - 2 end in [0, 2^32), the
  // top one holds the sign.
  for (int k = 0; k + 1 < kDigits; ++k) {
    const std::int64_t c = digits_[k] >> 32;
    digits_[k] -= c * (std::int64_t{1} << 32);
    digits_[k + 1] += c;
  }
  pending_ = 0;
}

double ExactSum::value() const {
  if (non_finite_ != 0) return std::numeric_limits<double>::quiet_NaN();
  ExactSum s = *this;
  s.carry();
  // Negative sums: the value of the negated digits, negated (the digits of -x after a carry
  // pass are those of x's magnitude once more carried).
  bool negative = s.digits_[kDigits - 1] < 0;
  if (negative) {
    for (std::int64_t& d : s.digits_) d = -d;
    s.carry();
  }
  int top = kDigits - 1;
  while (top >= 0 && s.digits_[top] == 0) --top;
  if (top < 0) return 0.0;
  // The three leading digits (65 to 96 bits) in a long double (64-bit significand), rounded
  // once more to double: within one unit in the last place of the exact sum.
  long double v = 0.0L;
  const int low = top >= 2 ? top - 2 : 0;
  for (int k = top; k >= low; --k) v = v * 4294967296.0L + static_cast<long double>(s.digits_[k]);
  const double out = static_cast<double>(std::ldexp(v, 32 * low - 1074));
  return negative ? -out : out;
}

void ExactSum::add(const ExactSum& other) {
  for (int k = 0; k < kDigits; ++k) digits_[k] += other.digits_[k];
  non_finite_ |= other.non_finite_;
  carry();
}

ExactSum ExactSum::reduced(MPI_Comm comm) const {
  ExactSum mine = *this;
  mine.carry();  // every digit below 2^32 in magnitude: the sum over ranks cannot overflow
  std::array<std::int64_t, kDigits + 1> words = mine.state();
  MPI_Allreduce(MPI_IN_PLACE, words.data(), kDigits + 1, MPI_INT64_T, MPI_SUM, comm);
  ExactSum out = from_state(words);
  out.non_finite_ = out.non_finite_ != 0 ? 1 : 0;
  out.carry();
  return out;
}

void ExactSum::reduce(std::span<ExactSum> sums, MPI_Comm comm) {
  std::vector<std::int64_t> words;
  words.reserve(sums.size() * (kDigits + 1));
  for (const ExactSum& s : sums) {
    const std::array<std::int64_t, kDigits + 1> w = s.state();  // carried: no overflow over ranks
    words.insert(words.end(), w.begin(), w.end());
  }
  MPI_Allreduce(MPI_IN_PLACE, words.data(), static_cast<int>(words.size()), MPI_INT64_T, MPI_SUM, comm);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    std::array<std::int64_t, kDigits + 1> w;
    std::copy_n(words.begin() + static_cast<std::ptrdiff_t>(k * (kDigits + 1)), kDigits + 1, w.begin());
    sums[k] = from_state(w);
    sums[k].non_finite_ = sums[k].non_finite_ != 0 ? 1 : 0;
    sums[k].carry();
  }
}

std::array<std::int64_t, ExactSum::kDigits + 1> ExactSum::state() const {
  ExactSum s = *this;
  s.carry();
  std::array<std::int64_t, kDigits + 1> out{};
  for (int k = 0; k < kDigits; ++k) out[k] = s.digits_[k];
  out[kDigits] = s.non_finite_;
  return out;
}

ExactSum ExactSum::from_state(const std::array<std::int64_t, kDigits + 1>& s) {
  ExactSum e;
  for (int k = 0; k < kDigits; ++k) e.digits_[k] = s[k];
  e.non_finite_ = s[kDigits];
  return e;
}

}  // namespace upgrain::dem
