#pragma once
// How much memory a scene needs at least, and how much this machine has (docs/input.md): the
// validation refuses a scene that cannot fit before anything is allocated or written, instead
// of failing late with std::bad_alloc or with the kernel's out-of-memory kill.
#include <string>

#include "coupling/scene_input.h"

namespace upgrain::coupling {

struct MemoryEstimate {
  double grains = 0.0;  // bytes: every grain (the state, its lists, rank 0's gathered copy)
  double cells = 0.0;   // bytes: the stress grid's and strain grid's cells
  double total = 0.0;   // bytes, with the process's own (libraries, buffers)
};

// A lower bound of rank 0's peak memory for `in` (measured figures per grain and per cell).
MemoryEstimate estimate_memory(const SceneInput& in);

// The memory this process may use: the machine's physical memory, or the control group's
// limit when that is lower.
double machine_memory();

// "1.2 GB", "340 MB".
std::string format_bytes(double bytes);

}  // namespace upgrain::coupling
