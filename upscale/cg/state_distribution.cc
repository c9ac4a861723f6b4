#include "upscale/cg/state_distribution.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>

#include "dem/core/error.h"
#include "dem/parallel/exchange.h"
#include "upscale/cg/periodic_images.h"

namespace upgrain::upscale::cg {

namespace {

struct Header {
  double time, gravity[3], longest_branch;
  std::uint64_t grains, branches, walls, with_displacement;
};

template <class T>
void put(std::vector<char>& out, const std::vector<T>& v) {
  const std::size_t at = out.size();
  out.resize(at + v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(out.data() + at, v.data(), v.size() * sizeof(T));
}

template <class T>
void take(const std::vector<char>& in, std::size_t& at, std::vector<T>& v, std::size_t n) {
  if (at + n * sizeof(T) > in.size()) throw Error("coarse graining: a state message is truncated");
  v.resize(n);
  if (n) std::memcpy(static_cast<void*>(v.data()), in.data() + at, n * sizeof(T));
  at += n * sizeof(T);
}

}  // namespace

std::vector<char> pack(const GrainState& s) {
  // The cell is not sent: the images go into the state before it is cut (state_for_points).
  if (s.cell.any()) throw Error("coarse graining: a state is sent before its periodic images were added");
  const Header h{s.time,
                 {s.gravity[0], s.gravity[1], s.gravity[2]},
                 s.longest_branch,
                 s.grains(),
                 s.branches(),
                 s.wall_contacts(),
                 s.with_displacement ? 1u : 0u};
  std::vector<char> out(sizeof(Header));
  std::memcpy(out.data(), &h, sizeof(Header));
  put(out, s.id);
  for (const auto* v : {&s.x, &s.v, &s.acceleration, &s.displacement}) put(out, *v);
  put(out, s.mass);
  put(out, s.volume);
  for (const auto* v : {&s.branch_from, &s.branch_to, &s.branch_force, &s.wall_point, &s.wall_force})
    put(out, *v);
  put(out, s.ends_at_grain);
  return out;
}

GrainState unpack(const std::vector<char>& in) {
  if (in.size() < sizeof(Header)) throw Error("coarse graining: a state message is truncated");
  Header h{};
  std::memcpy(&h, in.data(), sizeof(Header));
  GrainState s;
  s.time = h.time;
  s.gravity = Vec3(h.gravity[0], h.gravity[1], h.gravity[2]);
  s.longest_branch = h.longest_branch;
  s.with_displacement = h.with_displacement != 0;
  std::size_t at = sizeof(Header);
  take(in, at, s.id, h.grains);
  for (auto* v : {&s.x, &s.v, &s.acceleration}) take(in, at, *v, h.grains);
  take(in, at, s.displacement, s.with_displacement ? h.grains : 0);
  take(in, at, s.mass, h.grains);
  take(in, at, s.volume, h.grains);
  for (auto* v : {&s.branch_from, &s.branch_to, &s.branch_force}) take(in, at, *v, h.branches);
  for (auto* v : {&s.wall_point, &s.wall_force}) take(in, at, *v, h.walls);
  take(in, at, s.ends_at_grain, h.branches);
  if (at != in.size()) throw Error("coarse graining: a state message has trailing bytes");
  return s;
}

GrainState state_for_points(const GrainState& whole, std::span<const Vec3> points, double range,
                            MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // This rank's bounding box; an empty rank sends lo > hi.
  struct BoxRecord {
    double lo[3], hi[3];
  } mine{};
  for (int d = 0; d < 3; ++d) {
    mine.lo[d] = std::numeric_limits<double>::infinity();
    mine.hi[d] = -std::numeric_limits<double>::infinity();
  }
  for (const Vec3& r : points)
    for (int d = 0; d < 3; ++d) {
      mine.lo[d] = std::min(mine.lo[d], r[d]);
      mine.hi[d] = std::max(mine.hi[d], r[d]);
    }
  const std::vector<BoxRecord> boxes = dem::gather_to_root(std::vector<BoxRecord>{mine}, comm);
  GrainState own;
  if (rank == 0) {
    // A periodic cell's images first, once, in the whole state's order: a point near a face
    // then sees the grains across it, on any rank.
    std::optional<GrainState> imaged;
    if (whole.cell.any()) imaged = with_periodic_images(whole, range);
    const GrainState& source = imaged ? *imaged : whole;
    for (int r = 0; r < size; ++r) {
      dem::Box b;
      b.lo = Vec3(boxes[r].lo[0], boxes[r].lo[1], boxes[r].lo[2]);
      b.hi = Vec3(boxes[r].hi[0], boxes[r].hi[1], boxes[r].hi[2]);
      GrainState part = part_near(source, b, range);
      if (r == 0) {
        own = std::move(part);
        continue;
      }
      const std::vector<char> bytes = pack(part);
      if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw Error("coarse graining: a rank's part of the state is above 2 GB");
      const int n = static_cast<int>(bytes.size());
      MPI_Send(&n, 1, MPI_INT, r, 71, comm);
      MPI_Send(bytes.data(), n, MPI_BYTE, r, 72, comm);
    }
    return own;
  }
  int n = 0;
  MPI_Recv(&n, 1, MPI_INT, 0, 71, comm, MPI_STATUS_IGNORE);
  std::vector<char> bytes(static_cast<std::size_t>(n));
  MPI_Recv(bytes.data(), n, MPI_BYTE, 0, 72, comm, MPI_STATUS_IGNORE);
  return unpack(bytes);
}

}  // namespace upgrain::upscale::cg
