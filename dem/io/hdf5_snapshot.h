#pragma once
// Particle snapshots in HDF5 (one file per output step), particles sorted by global id so
// that files do not depend on the internal order (or, later, on the rank count).
#include <mpi.h>

#include <filesystem>
#include <string>
#include <vector>

#include "dem/core/particle_store.h"
#include "dem/core/plane_wall.h"

namespace upgrain::dem::io {

struct SnapshotInfo {
  std::string file;  // name relative to the XDMF file's folder
  double time = 0.0;
  long step = 0;
  long count = 0;
  bool shapes = false;  // ellipsoid datasets present (ParticleStore::has_shapes())
};

// Layout: /particles/{id, radius, position, velocity, angular_velocity, force}
// (position etc. are N x 3), /walls/{name (attribute list), point, normal, friction,
// force}; root attributes time (s), step, units, sign_convention. Scenes with ellipsoids
// add /particles/{each shape's description (dem/shape/shape_description.h: semi_axes, N x 3:
// a, b, c), orientation (N x 4: unit quaternion w, x, y, z, body -> world), shape_tensor
// (N x 9: Q diag(a, b, c) Q^T, row-major)}; radius is then the bounding radius a.
// A periodic cell's scene (`images`, docs/periodic.md) adds /particles/image (N x 3 int32: the
// crossings of each axis, unwrapped position = position + image L).
//
// Every rank of `comm` writes its rows into the one file with collective MPI-IO (parallel HDF5,
// hyperslab selections): `p` holds rows where.first .. where.first + p.size() - 1 of the
// where.total grains sorted by id (Simulation::whole_state_slice()), and no rank holds more.
// The walls and attributes are the same on every rank (rank 0 writes the walls' rows). The
// data sets' bytes do not depend on how the rows are divided, and neither do the file's
// (docs/output.md, "Snapshots"). Collective; an error is thrown on every rank.
struct SnapshotRows {
  long first = 0;
  long total = 0;
  bool images = false;  // a periodic cell's image counters
  bool shapes = false;  // the ellipsoid data sets (the scene's, also on a rank without grains)
};
void write_snapshot(MPI_Comm comm, const std::filesystem::path& path, const ParticleStore& p,
                    const SnapshotRows& where, const std::vector<PlaneWall>& walls,
                    const std::vector<Vec3>& wall_force, double time, long step);
// The same for a whole store on one process (any order: it is sorted by id first).
void write_snapshot(const std::filesystem::path& path, const ParticleStore& p,
                    const std::vector<PlaneWall>& walls, const std::vector<Vec3>& wall_force, double time,
                    long step, bool images = false);

// An XDMF 3 temporal collection over the snapshots, for ParaView (Xdmf3 reader):
// particles as a polyvertex grid with radius, velocity, angular velocity and force, and for
// ellipsoids the shape tensor, which ParaView's Tensor Glyph filter draws as the ellipsoids
// (sphere glyphs scaled by the eigenvalues a, b, c along the principal axes).
void write_xdmf(const std::filesystem::path& path, const std::vector<SnapshotInfo>& snapshots);

}  // namespace upgrain::dem::io
