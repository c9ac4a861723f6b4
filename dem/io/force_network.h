#pragma once
// The force network of a recorded step: every contact once, with its normal and tangential
// force and its overlap, written per snapshot as HDF5 with an XDMF file that draws each
// particle-particle contact as a line between the two centres (ParaView: force chains). In a
// periodic cell a pair across a face is evaluated, and drawn, with the second grain at its
// minimum image next to the first (docs/periodic.md). docs/output.md, "Force network".
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "dem/core/particle_store.h"
#include "dem/core/periodic_cell.h"
#include "dem/core/plane_wall.h"
#include "dem/parallel/records.h"

namespace upgrain::dem::io {

// One contact. For a pair: a < b (global ids), the force is the one on a; for a wall: a is the
// particle, wall the wall's index. The normal points from a to b (or into the wall).
struct NetworkContact {
  GlobalId a = 0;
  GlobalId b = -1;  // -1 for a wall contact
  int wall = -1;    // the wall's index, or -1 for a pair
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  // A pair's branch x_b - x_a, the minimum image in a periodic cell (Allen and Tildesley 2017,
  // sec. 1.6.2); zero for a wall. shift = branch - (x_b - x_a): the lattice vector that takes b
  // next to a, zero inside the cell (and always in a bounded box).
  Vec3 branch = Vec3::Zero();
  Vec3 shift = Vec3::Zero();
  Vec3 normal_force = Vec3::Zero();      // on a: (f . n) n
  Vec3 tangential_force = Vec3::Zero();  // on a: f - (f . n) n
  double overlap = 0.0;                  // m, > 0 in contact
};

// The grains a rank's share of the network is resolved against (Simulation::whole_state_slice()
// and add_other_rows()): its rows of the whole state sorted by id, ids first_row .. first_row +
// rows - 1 at indices 0 .. rows - 1, then the grains of other rows that its contacts reach,
// sorted by id. The whole state on one rank: first_row 0, every grain a row.
struct NetworkGrains {
  const ParticleStore& store;
  long first_row = 0;
  std::size_t rows = 0;

  // The store's index of grain `id`; throws upgrain::Error when it holds no such grain.
  [[nodiscard]] std::size_t index(GlobalId id) const;
};

// The contacts of `records` (every contact whose first grain is a row of `grains`, sorted by key:
// Simulation::contacts_by_id_slice(), or gather_contacts_by_id() with the whole state) resolved
// against the grains: the normal and overlap from the contact geometry of the two shapes
// (docs/ellipsoid-contact.md; spheres in closed form), the force split along it. A pair's
// geometry takes b at its minimum image in `cell` (a bounded cell: as it is).
std::vector<NetworkContact> force_network(const NetworkGrains& grains, const std::vector<PlaneWall>& walls,
                                          const std::vector<ContactRecord>& records,
                                          const PeriodicCell& cell);
// With the whole state sorted by id (ids 0..N-1 index `sorted_by_id`).
std::vector<NetworkContact> force_network(const ParticleStore& sorted_by_id,
                                          const std::vector<PlaneWall>& walls,
                                          const std::vector<ContactRecord>& records,
                                          const PeriodicCell& cell);

// The lines the XDMF draws: the N grains by id, then, for each pair whose b is an image (a
// non-zero shift), one node more at x_b + shift, next to a; nodes (M x 2) indexes them, so that
// no line crosses the cell. In a bounded box the positions are the grains' and the nodes the ids.
struct LineNodes {
  std::vector<Vec3> position;
  std::vector<std::int64_t> nodes;  // 2 per pair
};
// A rank's share: `position` holds its image nodes alone, the first of them node `first_image`
// of the whole (N plus the image nodes of the ranks before it).
LineNodes line_nodes(const NetworkGrains& grains, const std::vector<NetworkContact>& pairs, long first_image);
// The whole, from the whole state sorted by id.
LineNodes line_nodes(const ParticleStore& sorted_by_id, const std::vector<NetworkContact>& pairs);

struct NetworkInfo {
  std::string file;  // relative to the XDMF file's folder
  double time = 0.0;
  long step = 0;
  long particles = 0;
  long pairs = 0;
  long line_nodes = -1;  // rows of /lines/position; -1: a file written before /lines existed
};

// force_network/contacts_<step>.h5: /particles/position (N x 3, by id) and
// /contacts/{ids (M x 2), point, normal, branch, normal_force, tangential_force (M x 3), overlap,
// normal_force_magnitude, tangential_force_magnitude (M)} for the pairs; /wall_contacts/{particle,
// wall, point, normal, normal_force, tangential_force, overlap} for the walls; what the XDMF
// draws, /lines/{position, nodes} (line_nodes()). Root attributes time and step. Atomic
// (atomic_file.h).
// Every rank of `comm` writes its share into the one file (parallel HDF5, as the snapshots:
// docs/output.md): its rows of /particles/position, its contacts (those of its rows, in key
// order) at the rows that the ranks before it fill, its image nodes after those of the ranks
// before it. `total_grains`: N. The same data sets on any rank count. Collective.
NetworkInfo write_force_network(MPI_Comm comm, const std::filesystem::path& path, const NetworkGrains& grains,
                                long total_grains, const std::vector<NetworkContact>& contacts, double time,
                                long step);
// The whole on one process, from the whole state sorted by id.
NetworkInfo write_force_network(const std::filesystem::path& path, const ParticleStore& sorted_by_id,
                                const std::vector<NetworkContact>& contacts, double time, long step);

// An XDMF 3 temporal collection: each pair a two-node polyline (/lines), with the contact's
// values as cell data.
void write_force_network_xdmf(const std::filesystem::path& path, const std::vector<NetworkInfo>& files);

// The force network files of a run: force_network/contacts_<step>.h5, written by every rank of
// `comm` (write_force_network()), and force_network.xdmf in `folder`, rewritten by rank 0 with
// each file.
class ForceNetworkRecorder {
 public:
  ForceNetworkRecorder(MPI_Comm comm, std::filesystem::path folder)
      : comm_(comm), folder_(std::move(folder)) {}
  // Collective: each rank gives its share (force_network()).
  void write(const NetworkGrains& grains, long total_grains, const std::vector<PlaneWall>& walls,
             const std::vector<ContactRecord>& records, const PeriodicCell& cell, double time, long step);
  // A restart (rank 0): the files already in the folder (those after the checkpoint are gone)
  // listed again, by step.
  void resume();

 private:
  MPI_Comm comm_;
  std::filesystem::path folder_;
  std::vector<NetworkInfo> files_;  // rank 0
};

}  // namespace upgrain::dem::io
