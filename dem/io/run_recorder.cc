#include "dem/io/run_recorder.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "dem/core/error.h"
#include "dem/io/atomic_file.h"

namespace upgrain::dem::io {

namespace {
constexpr const char* kSeriesHeader =
    "# Upgrain time series. SI units (J, s). balance_error = (E_total - E_total(0)) / "
    "(initial kinetic + elastic energy + |potential energy released|); total = kinetic + potential + "
    "elastic + dissipated - tangential_stiffness_change\n"
    "time,step,kinetic_translational,kinetic_rotational,potential,elastic_normal,"
    "elastic_tangential,dissipated_damping,dissipated_friction,tangential_stiffness_change,total,balance_"
    "error,"
    "particle_contacts,wall_contacts,max_overlap_ratio,neighbor_builds\n";
}

RegularGrid stress_grid(const GridStressOptions& options, const ParticleStore& p, const BoxContainer& box) {
  RegularGrid g;
  for (int d = 0; d < 3; ++d) g.n[d] = options.cells[d];
  if (options.fixed_box) {
    g.lo = options.lo;
    g.hi = options.hi;
    return g;
  }
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.x[i].z() + p.radius[i]);
  g.lo = Vec3::Zero();
  g.hi = Vec3(box.lx, box.ly, top > 0.0 ? top : box.height);
  // The unconstrained collapse spreads past the footprint once the side walls are gone:
  // the grid then spans the grains' horizontal extent as well.
  if (box.opens_side_walls())
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int d = 0; d < 2; ++d) {
        g.lo[d] = std::min(g.lo[d], p.x[i][d] - p.radius[i]);
        g.hi[d] = std::max(g.hi[d], p.x[i][d] + p.radius[i]);
      }
  return g;
}

RunRecorder::RunRecorder(OutputOptions options)
    : options_(std::move(options)), series_(options_.folder / "time_series.csv", kSeriesHeader) {
  create_folder(options_.folder / "snapshots");
}

void RunRecorder::record_series(double time, long step, const EnergyBalance& e, double balance_error,
                                const StepDiagnostics& d) {
  char line[512];
  std::snprintf(line, sizeof line,
                "%.9g,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.6e,%ld,%ld,%.6e,%ld\n",
                time, step, e.kinetic_translational, e.kinetic_rotational, e.potential, e.elastic_normal,
                e.elastic_tangential, e.dissipated_damping, e.dissipated_friction,
                e.tangential_stiffness_change, e.total(), balance_error, d.particle_contacts, d.wall_contacts,
                d.max_overlap_ratio, d.neighbor_builds);
  rows_.emplace_back(line);
}

void RunRecorder::write_snapshot(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                                 const std::vector<Vec3>& wall_forces, double time, long step) {
  char name[64];
  std::snprintf(name, sizeof name, "particles_%09ld.h5", step);
  const std::filesystem::path rel = std::filesystem::path("snapshots") / name;
  io::write_snapshot(options_.folder / rel, p, walls, wall_forces, time, step);
  snapshots_.push_back({rel.string(), time, step, static_cast<long>(p.size()), p.has_shapes()});
  flush();
}

void RunRecorder::flush() {
  std::string text;
  for (; rows_written_ < rows_.size(); ++rows_written_) text += rows_[rows_written_];
  series_.append(text);
  write_xdmf(options_.folder / "particles.xdmf", snapshots_);
}

void RunRecorder::write_summary(const std::map<std::string, std::string>& entries) const {
  std::ostringstream j;
  j << "{\n";
  std::size_t k = 0;
  for (const auto& [key, value] : entries) {
    j << "  \"" << key << "\": " << value << (++k < entries.size() ? ",\n" : "\n");
  }
  j << "}\n";
  write_text_atomically(options_.folder / "summary.json", j.str());
}

}  // namespace upgrain::dem::io
