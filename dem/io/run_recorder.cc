#include "dem/io/run_recorder.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "dem/core/error.h"
#include "dem/io/atomic_file.h"

namespace upgrain::dem::io {

namespace {
constexpr const char* kSeriesHeader =
    "# Upgrain time series. SI units (J, s). total = kinetic + potential + elastic + dissipated + removed by "
    "relaxation - stiffness changes - work_by_walls (dem/engine/energy.h); balance_error = (total - "
    "total(0)) / (initial kinetic + elastic energy + |potential energy released| + |work_by_walls|)\n"
    "time,step,kinetic_translational,kinetic_rotational,potential,elastic_normal,"
    "elastic_tangential,dissipated_damping,dissipated_friction,tangential_stiffness_change,work_by_walls,"
    "total,"
    "balance_error,particle_contacts,wall_contacts,max_overlap_ratio,neighbor_builds\n";
}

RunRecorder::RunRecorder(std::filesystem::path folder)
    : folder_(std::move(folder)), series_(folder_ / "time_series.csv", kSeriesHeader) {
  create_folder(folder_ / "snapshots");
}

void RunRecorder::record_series(double time, long step, const EnergyBalance& e, double balance_error,
                                const StepDiagnostics& d) {
  char line[512];
  std::snprintf(
      line, sizeof line,
      "%.9g,%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.6e,%ld,%ld,%.6e,%ld\n", time,
      step, e.kinetic_translational, e.kinetic_rotational, e.potential, e.elastic_normal,
      e.elastic_tangential, e.dissipated_damping, e.dissipated_friction, e.tangential_stiffness_change,
      e.work_by_walls, e.total(), balance_error, d.particle_contacts, d.wall_contacts, d.max_overlap_ratio,
      d.neighbor_builds);
  rows_.emplace_back(line);
}

void RunRecorder::write_snapshot(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                                 const std::vector<Vec3>& wall_forces, double time, long step) {
  char name[64];
  std::snprintf(name, sizeof name, "particles_%09ld.h5", step);
  const std::filesystem::path rel = std::filesystem::path("snapshots") / name;
  io::write_snapshot(folder_ / rel, p, walls, wall_forces, time, step);
  snapshots_.push_back({rel.string(), time, step, static_cast<long>(p.size()), p.has_shapes()});
  flush();
}

void RunRecorder::flush() {
  std::string text;
  for (; rows_written_ < rows_.size(); ++rows_written_) text += rows_[rows_written_];
  series_.append(text);
  write_xdmf(folder_ / "particles.xdmf", snapshots_);
}

void RunRecorder::resume(const State& s) {
  series_.resume(s.series_rows);
  rows_.clear();
  rows_written_ = 0;
  snapshots_ = s.snapshots;
  write_xdmf(folder_ / "particles.xdmf", snapshots_);
}

void RunRecorder::write_summary(const std::map<std::string, std::string>& entries) const {
  std::ostringstream j;
  j << "{\n";
  std::size_t k = 0;
  for (const auto& [key, value] : entries) {
    j << "  \"" << key << "\": " << value << (++k < entries.size() ? ",\n" : "\n");
  }
  j << "}\n";
  write_text_atomically(folder_ / "summary.json", j.str());
}

}  // namespace upgrain::dem::io
