#pragma once
// How much memory a scene needs at least, and how much this process may use (docs/input.md): the
// validation refuses a scene that cannot fit before anything is allocated or written, instead
// of failing late with std::bad_alloc or with the kernel's out-of-memory kill.
#include <string>
#include <vector>

#include "coupling/input/scene_input.h"

namespace upgrain::coupling {

struct MemoryEstimate {
  double grains = 0.0;  // bytes: every grain (the state, its lists, rank 0's gathered copy)
  double cells = 0.0;   // bytes: the stress grid's and strain grid's cells
  double total = 0.0;   // bytes, with the process's own (libraries, buffers)
};

// A lower bound of rank 0's peak memory for `in` (measured figures per grain and per cell).
MemoryEstimate estimate_memory(const SceneInput& in);

// A limit on the memory this process may use, named as the user sets it, and what the process
// already counts against it (0: nothing beyond the estimate's own figure for the process).
struct MemoryLimit {
  std::string name;  // "this machine's physical memory", "ulimit -v (RLIMIT_AS)", ...
  double bytes = 0.0;
  double in_use = 0.0;
};

// Every limit that applies: the physical memory; the control group's (the process's own and its
// ancestors'); ulimit -v (RLIMIT_AS) and ulimit -d (RLIMIT_DATA) when set; a Slurm job's
// memory (SLURM_MEM_PER_NODE, SLURM_MEM_PER_CPU).
std::vector<MemoryLimit> memory_limits();

// "1.2 GB", "340 MB".
std::string format_bytes(double bytes);

}  // namespace upgrain::coupling
