#pragma once
// Particle snapshots in HDF5 (one file per output step), particles sorted by global id so
// that files do not depend on the internal order (or, later, on the rank count).
#include <filesystem>
#include <string>
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/core/particle_store.h"

namespace upgrain::dem::io {

struct SnapshotInfo {
  std::string file;  // name relative to the XDMF file's folder
  double time = 0.0;
  long step = 0;
  long count = 0;
};

// Layout: /particles/{id, radius, position, velocity, angular_velocity, force}
// (position etc. are N x 3), /walls/{name (attribute list), point, normal, friction,
// force}; root attributes time (s), step, units, sign_convention.
void write_snapshot(const std::filesystem::path& path, const ParticleStore& p,
                    const std::vector<PlaneWall>& walls, const std::vector<Vec3>& wall_force, double time,
                    long step);

// An XDMF 3 temporal collection over the snapshots, for ParaView (Xdmf3 reader):
// particles as a polyvertex grid with radius, velocity, angular velocity and force.
void write_xdmf(const std::filesystem::path& path, const std::vector<SnapshotInfo>& snapshots);

}  // namespace upgrain::dem::io
