#pragma once
// Two lanes of doubles (GCC and Clang vector extension: SSE2 on x86-64, NEON on AArch64), for
// kernels written once over "lanes" T = double (one item) or T = Pair (two items side by side):
// the rotation of two grains (motion/grain_rotation.cc) and the Newton solve of two contact pairs
// (contact/warm_newton.h). Each lane of a Pair rounds as the double code does, so an item gets
// the same bits either way (with -ffp-contract=off, dem/CMakeLists.txt).
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace upgrain::dem::lanes {

using Pair = double __attribute__((vector_size(16)));
using Mask = long long __attribute__((vector_size(16)));  // a comparison of two Pairs: 0 or -1

inline double sqrt_of(double x) { return std::sqrt(x); }
inline Pair sqrt_of(Pair x) {
#if defined(__SSE2__)
  return _mm_sqrt_pd(x);  // correctly rounded in each lane, as std::sqrt
#else
  return Pair{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}
inline double sign_of(double z) { return std::copysign(1.0, z); }
inline Pair sign_of(Pair z) { return Pair{std::copysign(1.0, z[0]), std::copysign(1.0, z[1])}; }

}  // namespace upgrain::dem::lanes
