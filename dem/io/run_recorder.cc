#include "dem/io/run_recorder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"

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

constexpr const char* kWallsHeader =
    "# Upgrain walls. SI units (m, m/s, N). One row per wall and time-series row; n = the wall's unit normal "
    "into the grains; displacement = (point - point at its first row).n; normal_force = -F.n (compression "
    "positive), shear_force = |F - (F.n) n|, F = the force the particles exert on the wall (docs/output.md)\n"
    "time,step,wall,point_x,point_y,point_z,displacement,velocity_x,velocity_y,velocity_z,normal_force,"
    "shear_force,force_x,force_y,force_z\n";
}  // namespace

RunRecorder::RunRecorder(std::filesystem::path folder)
    : folder_(std::move(folder)),
      series_(folder_ / "time_series.csv", kSeriesHeader),
      walls_(folder_ / "walls.csv", kWallsHeader) {
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

void RunRecorder::record_walls(double time, long step, const std::vector<PlaneWall>& walls,
                               const std::vector<bool>& present, const std::vector<Vec3>& wall_forces) {
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!present[w]) continue;
    const PlaneWall& wall = walls[w];
    // A wall's first row (the run's start, or the row after it was added) is its origin.
    if (wall_origins_.size() <= w) wall_origins_.resize(w + 1, Vec3::Constant(std::nan("")));
    if (!wall_origins_[w].allFinite()) wall_origins_[w] = wall.point;
    const Vec3& f = wall_forces[w];
    const double fn = f.dot(wall.normal);
    const double pressing = -fn + 0.0;  // + 0.0: no "-0" in the table
    char line[512];
    std::snprintf(line, sizeof line,
                  "%.9g,%ld,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                  time, step, wall.name.c_str(), wall.point.x(), wall.point.y(), wall.point.z(),
                  (wall.point - wall_origins_[w]).dot(wall.normal), wall.velocity.x(), wall.velocity.y(),
                  wall.velocity.z(), pressing, (f - fn * wall.normal).norm(), f.x(), f.y(), f.z());
    wall_rows_.emplace_back(line);
  }
}

void RunRecorder::write_snapshot(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                                 const std::vector<Vec3>& wall_forces, double time, long step, bool images) {
  const std::filesystem::path rel = snapshot_name(step);
  io::write_snapshot(folder_ / rel, p, walls, wall_forces, time, step, images);
  add_snapshot({rel.string(), time, step, static_cast<long>(p.size()), p.has_shapes()});
}

std::filesystem::path RunRecorder::snapshot_name(long step) {
  char name[64];
  std::snprintf(name, sizeof name, "particles_%09ld.h5", step);
  return std::filesystem::path("snapshots") / name;
}

void RunRecorder::add_snapshot(const SnapshotInfo& s) {
  snapshots_.push_back(s);
  flush();
}

void RunRecorder::flush() {
  std::string text;
  for (; rows_written_ < rows_.size(); ++rows_written_) text += rows_[rows_written_];
  series_.append(text);
  text.clear();
  for (; wall_rows_written_ < wall_rows_.size(); ++wall_rows_written_) text += wall_rows_[wall_rows_written_];
  walls_.append(text);
  write_xdmf(folder_ / "particles.xdmf", snapshots_);
}

void RunRecorder::resume(const State& s) {
  series_.resume(s.series_rows);
  rows_.clear();
  rows_written_ = 0;
  walls_.resume(s.wall_rows);
  wall_rows_.clear();
  wall_rows_written_ = 0;
  wall_origins_ = s.wall_origins;
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
