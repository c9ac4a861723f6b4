#pragma once
// What a coarse-graining kernel is (docs/coarse-graining.md): a small value type with
//   name, width(), cutoff(),
//   value(r2)                      phi at squared distance r2 (phi integrates to 1 in 3D),
//   value_and_gradient_factor(r2)  phi and g with grad phi(d) = g d,
//   line_integral(d, l)            int_0^1 phi(|d - s l|) ds along a branch l.
// GaussianKernel (gaussian_kernel.h) and LucyKernel (lucy_kernel.h) are the two; another is
// one file with these members, its rows in kernel_kind.h (KernelKind, its name, with_kernel)
// and its name among the choices of CoarseGraining/kernel
// (coupling/studies/continuum/coarse_graining_section.cc).
#include <concepts>

#include "dem/core/types.h"

namespace upgrain::upscale::cg {

using dem::GlobalId;
using dem::Mat3;
using dem::Vec3;

struct KernelValue {
  double phi;
  double gradient_factor;  // grad phi(d) = gradient_factor * d
};

template <class K>
concept Kernel = requires(const K k, double r2, const Vec3& d) {
  { K::name } -> std::convertible_to<const char*>;
  { k.width() } -> std::convertible_to<double>;
  { k.cutoff() } -> std::convertible_to<double>;
  { k.value(r2) } -> std::convertible_to<double>;
  { k.value_and_gradient_factor(r2) } -> std::convertible_to<KernelValue>;
  { k.line_integral(d, d) } -> std::convertible_to<double>;
};

}  // namespace upgrain::upscale::cg
