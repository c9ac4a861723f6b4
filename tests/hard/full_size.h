#pragma once
// The hard cases run reduced in CI; bench/hard_cases.sh runs the same tests at full size
// (UPGRAIN_HARD_FULL=1), where a case takes minutes (docs/hard-cases.md).
#include <cstdlib>

namespace upgrain::test {

inline bool hard_full_size() {
  const char* e = std::getenv("UPGRAIN_HARD_FULL");
  return e != nullptr && e[0] == '1';
}

// `reduced` in CI, `full` from bench/hard_cases.sh.
inline long hard_size(long reduced, long full) { return hard_full_size() ? full : reduced; }

}  // namespace upgrain::test
