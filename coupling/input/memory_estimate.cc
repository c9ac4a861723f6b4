#include "coupling/input/memory_estimate.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

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

// A number of bytes in a file (a control group's limit); 0 when absent or "max" (no limit).
double bytes_in(const std::string& file) {
  std::ifstream in(file);
  double limit = 0.0;
  return in >> limit && limit > 0.0 ? limit : 0.0;
}

// The tightest memory limit of this process's control group and its ancestors (a batch system's
// job cgroup is a descendant of the root, whose file says nothing): cgroup v2 memory.max, v1
// memory.limit_in_bytes (its "no limit" is a number near 2^63, above any machine).
MemoryLimit cgroup_limit() {
  MemoryLimit best{"the control group's limit", 0.0, 0.0};
  auto take = [&](double bytes, const std::string& file) {
    if (bytes > 0.0 && (best.bytes == 0.0 || bytes < best.bytes)) {
      best.bytes = bytes;
      best.name = "the control group's limit (" + file + ")";
    }
  };
  std::ifstream groups("/proc/self/cgroup");
  std::string line;
  while (std::getline(groups, line)) {
    // "0::/path" (v2) or "4:memory:/path" (v1).
    const std::size_t a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1);
    const bool v2 = controllers.empty(), v1 = controllers == "memory";
    if (!v2 && !v1) continue;
    const std::string root = v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
    const char* name = v2 ? "memory.max" : "memory.limit_in_bytes";
    for (std::string path = line.substr(b + 1);; path = path.substr(0, path.rfind('/'))) {
      const std::string file = root + (path == "/" ? "" : path) + "/" + name;
      take(bytes_in(file), file);
      if (path.empty() || path == "/") break;
    }
  }
  // A container's own view: its cgroup is its root.
  for (const char* file : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"})
    take(bytes_in(file), file);
  return best;
}

// A field of /proc/self/status in bytes ("VmSize:  123456 kB"); 0 when absent.
double status_bytes(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(field + ":", 0) == 0) return 1024.0 * std::atof(line.c_str() + field.size() + 1);
  return 0.0;
}

// A resource limit of this process (ulimit -v, -d); 0 when unlimited.
double resource_limit(int resource) {
  struct rlimit l {};
  if (::getrlimit(resource, &l) != 0 || l.rlim_cur == RLIM_INFINITY) return 0.0;
  return static_cast<double>(l.rlim_cur);
}

// A batch system's memory in megabytes (Slurm's --mem and --mem-per-cpu: SLURM_MEM_PER_NODE,
// SLURM_MEM_PER_CPU, in MB of 2^20 bytes); 0 when unset or not a number.
double slurm_megabytes(const char* variable) {
  const char* text = std::getenv(variable);
  if (text == nullptr) return 0.0;
  char* end = nullptr;
  const double mb = std::strtod(text, &end);
  return end != text && *end == '\0' && mb > 0.0 ? mb * 1048576.0 : 0.0;
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

std::vector<MemoryLimit> memory_limits() {
  std::vector<MemoryLimit> limits;
  limits.push_back(
      {"this machine's physical memory",
       static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE)), 0.0});
  if (MemoryLimit c = cgroup_limit(); c.bytes > 0.0) limits.push_back(c);
  // The address space counts every mapping, the libraries' and MPI's reservations too: what the
  // process holds now is taken from it.
  if (const double as = resource_limit(RLIMIT_AS); as > 0.0)
    limits.push_back({"ulimit -v (RLIMIT_AS)", as, status_bytes("VmSize")});
  if (const double data = resource_limit(RLIMIT_DATA); data > 0.0)
    limits.push_back({"ulimit -d (RLIMIT_DATA)", data, status_bytes("VmData")});
  // Slurm enforces a job's memory per node with a control group of the job, which the process
  // may not see under /sys/fs/cgroup; its request is in the environment. (PBS passes no such
  // variable: its per-process limits reach the process as the resource limits above.)
  if (const double node = slurm_megabytes("SLURM_MEM_PER_NODE"); node > 0.0)
    limits.push_back({"Slurm's memory per node (SLURM_MEM_PER_NODE)", node, 0.0});
  if (const double cpu = slurm_megabytes("SLURM_MEM_PER_CPU"); cpu > 0.0) {
    const char* cpus = std::getenv("SLURM_CPUS_ON_NODE");
    const double n = cpus != nullptr ? std::max(1.0, std::atof(cpus)) : 1.0;
    limits.push_back({cpus != nullptr
                          ? "Slurm's memory per CPU times the CPUs of the node (SLURM_MEM_PER_CPU x "
                            "SLURM_CPUS_ON_NODE)"
                          : "Slurm's memory per CPU (SLURM_MEM_PER_CPU)",
                      cpu * n, 0.0});
  }
  return limits;
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
