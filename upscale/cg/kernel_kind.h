#pragma once
// The kernels by name, for the scene file and the run-time choice: one row each in
// with_kernel(). docs/coarse-graining.md.
#include <optional>
#include <string>
#include <string_view>

#include "dem/core/error.h"
#include "upscale/cg/gaussian_kernel.h"
#include "upscale/cg/lucy_kernel.h"

namespace upgrain::upscale::cg {

enum class KernelKind { gaussian, lucy };

[[nodiscard]] inline std::string_view name_of(KernelKind k) {
  return k == KernelKind::gaussian ? GaussianKernel::name : LucyKernel::name;
}
[[nodiscard]] inline std::optional<KernelKind> kernel_from_name(std::string_view s) {
  if (s == GaussianKernel::name) return KernelKind::gaussian;
  if (s == LucyKernel::name) return KernelKind::lucy;
  return std::nullopt;
}

// A kernel and its width (m), as chosen at run time.
struct KernelChoice {
  KernelKind kind = KernelKind::gaussian;
  double width = 0.0;
};

// Calls f(kernel) with the kernel type of the choice.
template <class F>
decltype(auto) with_kernel(const KernelChoice& c, F&& f) {
  if (!(c.width > 0.0)) throw Error("coarse graining: the kernel width must be positive");
  switch (c.kind) {
    case KernelKind::gaussian:
      return f(GaussianKernel(c.width));
    case KernelKind::lucy:
      return f(LucyKernel(c.width));
  }
  throw Error("coarse graining: unknown kernel");
}

// The cut-off of the choice (m).
[[nodiscard]] inline double cutoff_of(const KernelChoice& c) {
  return with_kernel(c, [](const auto& k) { return k.cutoff(); });
}

}  // namespace upgrain::upscale::cg
