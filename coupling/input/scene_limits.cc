#include "coupling/input/scene_limits.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "coupling/input/memory_estimate.h"
#include "coupling/run/folder_lock.h"
#include "coupling/run/output_folder.h"
#include "dem/core/error.h"
#include "dem/engine/simulation.h"
#include "dem/files/output_manifest.h"
#include "dem/scene/gradation.h"
#include "dem/scene/weight_overlap.h"

namespace upgrain::coupling {

void check_gradation_sampling(const SceneInput& in, const std::string& where) {
  const std::vector<dem::GradationPoint>& curve = in.scene.particles.gradation;
  if (curve.empty()) return;
  // About 10^8 draws take a second; 10^9 is where --check would sit for half a minute.
  constexpr double kMostDraws = 1e9;
  const double acceptance = dem::sampling_acceptance(curve);
  // The fill's grains and a pour's (docs/insertion.md), each drawn the same way.
  const long count = std::max(in.scene.particles.count, in.scene.insertion.count);
  const char* entry =
      in.scene.particles.count >= in.scene.insertion.count ? "Particles/count" : "Insertion/count";
  const double draws = static_cast<double>(count) / acceptance;
  if (draws <= kMostDraws) return;
  std::ostringstream m;
  m.precision(3);
  m << where << "Particles/gradation spans radii " << curve.front().radius << " to " << curve.back().radius
    << " m: drawing " << entry << " = " << count << " grains by their mass fractions accepts one draw in "
    << 1.0 / acceptance << " (about " << draws << " draws, more than " << kMostDraws
    << "); raise the smallest radius or use fewer grains";
  throw Error(m.str());
}

void check_memory(const SceneInput& in, const std::string& where) {
  const MemoryEstimate need = estimate_memory(in);
  // Against every limit that applies; the one with the least room left names the refusal.
  const MemoryLimit* tightest = nullptr;
  double need_there = 0.0, room = 0.0;
  const std::vector<MemoryLimit> limits = memory_limits();
  for (const MemoryLimit& l : limits) {
    // What the process holds already, where the limit counts it, instead of the estimate's figure.
    const double n = l.in_use > 0.0 ? l.in_use + need.grains + need.cells : need.total;
    if (tightest == nullptr || l.bytes - n < room) {
      tightest = &l;
      need_there = n;
      room = l.bytes - n;
    }
  }
  if (tightest == nullptr || room >= 0.0) return;
  const dem::io::GridStressOptions& gs = in.output.grid_stress;
  std::ostringstream m;
  m << where << "the scene needs at least " << format_bytes(need_there)
    << " of memory (Particles/count = " << in.scene.particles.count
    << (in.scene.insertion.enabled() ? " + Insertion/count = " + std::to_string(in.scene.insertion.count)
                                     : "")
    << ": " << format_bytes(need.grains);
  if (need.cells > 0.0)
    m << "; Stress/grid cells = " << gs.cells[0] << ", " << gs.cells[1] << ", " << gs.cells[2] << ": "
      << format_bytes(need.cells);
  if (tightest->in_use > 0.0) m << "; the process itself: " << format_bytes(tightest->in_use);
  m << "), more than the " << format_bytes(tightest->bytes) << " this process may use by " << tightest->name
    << "; use fewer grains or cells";
  if (tightest != &limits.front()) m << ", or raise that limit";
  throw Error(m.str());
}

void check_output_folder(const SceneInput& in, const std::string& where) {
  namespace fs = std::filesystem;
  const fs::path& folder = in.output.folder;
  const std::string entry = where + "Output/folder = '" + folder.string() + "'";
  if (folder.empty()) throw Error(where + "Output/folder is empty; name the folder for the results");
  std::error_code ec;
  if (fs::exists(folder, ec)) {
    if (!fs::is_directory(folder, ec)) throw Error(entry + " exists and is not a folder");
    if (const std::string who = lock_holder(folder); !who.empty())
      throw Error(entry + " is in use by another run of upgrain (" + who +
                  "); wait for it to end, or stop it");
    if (in.restarting && !dem::io::has_manifest(folder))
      throw Error(entry + " holds no manifest of a run (" + dem::io::manifest_path(folder).string() +
                  "), so a restart cannot tell the run's files from others; it was not written by this "
                  "version of upgrain");
    if (!holds_no_results(folder) && !in.restarting) {
      if (!in.overwrite) {
        // A run that did not finish is continued, not replaced by accident.
        const bool interrupted = dem::io::has_manifest(folder) &&
                                 fs::is_directory(folder / "checkpoints", ec) &&
                                 dem::io::read_manifest(folder).status != "finished";
        if (interrupted)
          throw Error(entry + " holds a run that did not finish; continue it with 'upgrain --restart " +
                      folder.string() +
                      "', or choose another folder ('--output DIR' on the command line), or set "
                      "'Output/overwrite = true' to replace it");
        throw Error(entry +
                    " already holds results; choose another folder ('--output DIR' on the command line) or "
                    "set 'Output/overwrite = true'");
      }
      if (const std::string why = why_not_replaceable(folder); !why.empty()) throw Error(entry + " " + why);
    }
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
      throw Error(entry + " cannot be written: " + std::strerror(errno));
    return;
  }
  // The folder is made at the start of the run, under its nearest existing ancestor: that
  // must be a folder this process can write into (a read-only file system refuses even root).
  fs::path ancestor = fs::absolute(folder, ec).parent_path();
  while (!ancestor.empty() && !fs::exists(ancestor, ec) && ancestor != ancestor.root_path())
    ancestor = ancestor.parent_path();
  if (!fs::is_directory(ancestor, ec))
    throw Error(entry + " cannot be created: " + ancestor.string() + " is a file, not a folder");
  if (::access(ancestor.c_str(), W_OK | X_OK) != 0)
    throw Error(entry + " cannot be created in " + ancestor.string() + ": " + std::strerror(errno));
}

void check_output_intervals(const SceneInput& in, const std::string& where) {
  const double dt = in.scene.time_step;
  const struct {
    const char* entry;
    double value;
  } intervals[] = {
      {"Output/snapshot interval", in.output.snapshot_interval},
      {"Output/time series interval", in.output.series_interval},
      {"Stress/interval", in.output.grid_stress.enabled() ? in.output.grid_stress.interval : 0.0},
      {"Checkpoint/interval", in.output.checkpoint.interval}};
  for (const auto& i : intervals) {
    // 0 means "none" or "with the snapshots"; anything below one step would write at every
    // step, thousands of files or rows a minute.
    if (i.value > 0.0 && i.value < dt) {
      std::ostringstream m;
      m << where << i.entry << " = " << i.value << " s is shorter than Simulation/time step = " << dt
        << " s: it would write at every step; give at least one time step";
      throw Error(m.str());
    }
  }
}

void check_fill_height(SceneInput& in, double fill_top, const std::string& where) {
  const dem::SceneConfig& s = in.scene;
  const double height = s.container.height;
  if (s.fill.bottom_gap >= height) {
    std::ostringstream m;
    m << where << "Fill/bottom gap = " << s.fill.bottom_gap
      << " m puts every grain above the container (Container/height = " << height << " m)";
    throw Error(m.str());
  }
  if (fill_top > height) {
    std::ostringstream m;
    m.precision(3);
    m << where << "the fill stacks the grains up to z = " << fill_top << " m, " << fill_top / height
      << " times Container/height = " << height
      << " m: the walls are unbounded planes and hold them, but a box of that height would overflow; raise "
         "the height or lower Particles/count";
    in.warnings.push_back(m.str());
  }
}

void check_stiffness(SceneInput& in, const std::string& where) {
  const double ratio = dem::weight_overlap_ratio(in.scene);
  if (ratio <= dem::kStaticOverlapBound) return;
  std::ostringstream m;
  m.precision(3);
  m << where << "the grains are too soft for their weight: by the " << in.scene.contact_law
    << " law a grain's weight alone presses it " << ratio
    << " of a radius into the floor (DEM keeps static overlaps below " << dem::kStaticOverlapBound
    << "); raise Particles/youngs modulus (now " << in.scene.particles.material.youngs_modulus
    << " Pa) or the law's stiffness";
  // Beyond the guard's limit the run would stop at the first contact, whatever the time step.
  if (ratio >= dem::kRunawayOverlapRatio) {
    m << ": the run would stop at the runaway-overlap limit of " << dem::kRunawayOverlapRatio
      << " of a radius";
    throw Error(m.str());
  }
  in.warnings.push_back(m.str());
}

void check_stress_box(const SceneInput& in, double fill_top, const std::string& where) {
  const dem::io::GridStressOptions& gs = in.output.grid_stress;
  if (!gs.enabled() || !gs.fixed_box) return;
  const dem::BoxContainer& c = in.scene.container;
  // Where grains can be: between the walls (anywhere along x and y once the unconstrained
  // collapse removes them), from the floor up to the higher of the wall height and the fill.
  const bool walls_stay = in.collapse != "unconstrained";
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {c.lx, c.ly, std::max(c.height, fill_top)};
  for (int d = 0; d < 3; ++d) {
    const bool bounded = d == 2 || walls_stay;
    const bool outside = gs.hi[d] <= lo[d] || (bounded && gs.lo[d] >= hi[d]);
    const bool beyond = d == 2 ? gs.lo[d] < lo[d] : walls_stay && (gs.lo[d] < lo[d] || gs.hi[d] > hi[d]);
    if (!outside && !beyond) continue;
    std::ostringstream m;
    m << where << "Stress/box = '" << in.stress_box << "' spans [" << gs.lo[d] << ", " << gs.hi[d]
      << "] m along "
      << "xyz"[d] << ", ";
    if (outside)
      m << "entirely outside the container ([" << lo[d] << ", " << hi[d]
        << "] m): its cells would hold no grain";
    else if (d == 2)
      m << "below the container's floor (z = 0): the cells there would be partly empty and their stress too "
           "low";
    else
      m << "beyond the container's walls ([0, " << hi[d]
        << "] m): the cells there would be partly empty and their stress too low";
    throw Error(m.str());
  }
}

}  // namespace upgrain::coupling
