#include "coupling/memory_estimate.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace upgrain::coupling {

namespace {

// Peak resident memory of `upgrain` measured on a few steps of a deposition (GNU time's maximum
// resident set size): 1,000 and 20,000 spheres differ by 3.0 kB per grain; 40^3 stress cells
// with the 7 formulas and no strain add 2.72 kB per cell (0.39 kB per cell and formula), with
// strain 8.67 kB per cell at 40^3 and at 80^3 alike (5.95 kB more); the process itself
// (deal.II, MPI, HDF5 loaded) starts at 176 MB. A settled bed's contacts only add to the
// per-grain figure, so the estimate is a lower bound.
constexpr double kBytesPerGrain = 3.0e3;
constexpr double kBytesPerCellAndFormula = 0.39e3;
constexpr double kBytesPerStrainCell = 5.95e3;
constexpr double kBytesOfProcess = 176e6;

double cgroup_limit() {
  for (const char* file : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(file);
    double limit = 0.0;
    if (in >> limit && limit > 0.0) return limit;  // "max" (no limit) does not read as a number
  }
  return 0.0;
}

}  // namespace

MemoryEstimate estimate_memory(const SceneInput& in) {
  MemoryEstimate m;
  // With a pour (docs/insertion.md), the grains it brings too.
  m.grains = kBytesPerGrain * static_cast<double>(in.scene.particles.count + in.scene.insertion.count);
  const dem::io::GridStressOptions& gs = in.output.grid_stress;
  if (gs.enabled()) {
    const double cells = static_cast<double>(gs.cells[0]) * gs.cells[1] * gs.cells[2];
    m.cells = cells * (kBytesPerCellAndFormula * static_cast<double>(gs.formulas.size()) +
                       (in.output.grid_strain.enabled ? kBytesPerStrainCell : 0.0));
  }
  m.total = kBytesOfProcess + m.grains + m.cells;
  return m;
}

double machine_memory() {
  const double physical =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  const double limit = cgroup_limit();
  return limit > 0.0 ? std::min(physical, limit) : physical;
}

std::string format_bytes(double bytes) {
  char text[32];
  if (bytes >= 1e12)
    std::snprintf(text, sizeof text, "%.3g TB", bytes / 1e12);
  else if (bytes >= 1e9)
    std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  else
    std::snprintf(text, sizeof text, "%.3g MB", bytes / 1e6);
  return text;
}

}  // namespace upgrain::coupling
