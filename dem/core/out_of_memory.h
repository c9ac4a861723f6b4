#pragma once
// An allocation that fails says what was being allocated (docs/input.md, "Memory"). The scene's
// memory check (coupling/input/scene_limits.h) refuses a scene that cannot fit before anything is
// allocated, but its estimate is a lower bound; a run that still runs out of memory would end
// with a bare std::bad_alloc. The run's big allocations (the fill, the engine's particle store
// and lists, the grids, snapshots, checkpoints, the continuum's system) are made inside
// `allocating`, which turns std::bad_alloc into upgrain::Error naming them. Files are written
// whole or not at all (dem/files/atomic_file.h), so nothing is left half-written.
#include <new>
#include <string>
#include <utility>

#include "dem/core/error.h"

namespace upgrain {

class OutOfMemory : public Error {
 public:
  using Error::Error;
};

// `what`: what was being allocated, e.g. "the fill's grains".
[[noreturn]] inline void throw_out_of_memory(const char* what) {
  throw OutOfMemory(std::string("out of memory while allocating ") + what +
                    " (std::bad_alloc): the run needs more memory than this process may use (its limits: "
                    "docs/input.md, \"Memory\")");
}

// work(), with std::bad_alloc turned into OutOfMemory naming `what`. An inner `allocating`
// names the allocation more closely; its error passes through.
template <class Work>
decltype(auto) allocating(const char* what, Work&& work) {
  try {
    return std::forward<Work>(work)();
  } catch (const std::bad_alloc&) {
    throw_out_of_memory(what);
  }
}

}  // namespace upgrain
