#include "dem/io/force_network.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "dem/contact/geometry/pair_geometries.h"
#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/io/hdf5_reader.h"
#include "dem/io/hdf5_util.h"
#include "dem/parallel/exchange.h"

namespace upgrain::dem::io {

namespace {

using hdf5::Handle;
using hdf5::write_attribute;

void split_force(NetworkContact& c, const Vec3& force) {
  c.normal_force = force.dot(c.normal) * c.normal;
  c.tangential_force = force - c.normal_force;
}

std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out(3 * v.size());
  for (std::size_t k = 0; k < v.size(); ++k)
    for (int d = 0; d < 3; ++d) out[3 * k + d] = v[k][d];
  return out;
}

// A group of contacts: this rank's rows first .. first + cs.size() - 1 of `total`.
struct ContactRows {
  MPI_Comm comm;
  hsize_t total;
  hsize_t first;
};

void write_contacts(hid_t file, const char* group_name, const std::vector<NetworkContact>& cs, bool pairs,
                    const ContactRows& where) {
  Handle g(hdf5::create_group(file, group_name), H5Gclose, std::string("create group ") + group_name);
  const std::size_t m = cs.size();
  auto rows = [&](const char* name, const auto* data, hsize_t cols) {
    hdf5::write_rows(where.comm, g, name, data, where.total, cols, where.first, m);
  };
  auto vectors = [&](const char* name, Vec3 NetworkContact::*field) {
    std::vector<double> flat(3 * m);
    for (std::size_t k = 0; k < m; ++k)
      for (int d = 0; d < 3; ++d) flat[3 * k + d] = (cs[k].*field)[d];
    rows(name, flat.data(), 3);
  };
  std::vector<double> overlap(m), fn(m), ft(m);
  std::vector<std::int64_t> first(m), second(pairs ? 2 * m : m);
  for (std::size_t k = 0; k < m; ++k) {
    overlap[k] = cs[k].overlap;
    fn[k] = cs[k].normal_force.norm();
    ft[k] = cs[k].tangential_force.norm();
    if (pairs) {
      second[2 * k] = cs[k].a;
      second[2 * k + 1] = cs[k].b;
    } else {
      first[k] = cs[k].a;
      second[k] = cs[k].wall;
    }
  }
  if (pairs) {
    rows("ids", second.data(), 2);
  } else {
    rows("particle", first.data(), 1);
    rows("wall", second.data(), 1);
  }
  vectors("point", &NetworkContact::point);
  vectors("normal", &NetworkContact::normal);
  if (pairs) vectors("branch", &NetworkContact::branch);
  vectors("normal_force", &NetworkContact::normal_force);
  vectors("tangential_force", &NetworkContact::tangential_force);
  rows("overlap", overlap.data(), 1);
  rows("normal_force_magnitude", fn.data(), 1);
  rows("tangential_force_magnitude", ft.data(), 1);
}

}  // namespace

std::size_t NetworkGrains::index(GlobalId id) const {
  const long row = id - first_row;
  std::size_t k = store.size();
  if (row >= 0 && row < static_cast<long>(rows)) {
    k = static_cast<std::size_t>(row);
  } else {
    const auto others = store.id.begin() + static_cast<std::ptrdiff_t>(rows);
    const auto it = std::lower_bound(others, store.id.end(), id);
    if (it != store.id.end() && *it == id) k = static_cast<std::size_t>(it - store.id.begin());
  }
  if (k >= store.size() || store.id[k] != id)
    throw Error("force network: grain " + std::to_string(id) + " is not in the state it is resolved against");
  return k;
}

std::vector<NetworkContact> force_network(const NetworkGrains& grains, const std::vector<PlaneWall>& walls,
                                          const std::vector<ContactRecord>& records,
                                          const PeriodicCell& cell) {
  const ParticleStore& p = grains.store;
  std::vector<NetworkContact> out;
  out.reserve(records.size());
  ContactSolverStats stats;
  for (const ContactRecord& r : records) {
    const std::size_t a = grains.index(r.a);
    NetworkContact c;
    c.a = r.a;
    c.point = get(r.point);
    if (r.b >= 0) {
      const std::size_t b = grains.index(r.b);
      c.b = r.b;
      // The centres a cell apart for a pair across a face: b's image next to a instead, moved
      // by a lattice vector (exact on the cell's grid: the bits of the pair inside the cell).
      const Vec3 d = p.x[b] - p.x[a];
      c.branch = minimum_image(cell, d);
      c.shift = c.branch - d;
      const ContactGeometry g =
          pair_contact(p, a, b, stats, c.shift);  // the pair's row of the geometry table
      c.normal = g.normal;
      c.overlap = g.depth;
    } else {
      c.wall = static_cast<int>(-1 - r.b);
      const PlaneWall& w = walls.at(static_cast<std::size_t>(c.wall));
      // Into the wall; the overlap is how far the grain reaches behind the plane.
      c.normal = -w.normal;
      c.overlap = wall_depth(p, a, w);
    }
    split_force(c, get(r.force));
    out.push_back(c);
  }
  return out;
}

std::vector<NetworkContact> force_network(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                                          const std::vector<ContactRecord>& records,
                                          const PeriodicCell& cell) {
  return force_network(NetworkGrains{p, 0, p.size()}, walls, records, cell);
}

LineNodes line_nodes(const NetworkGrains& grains, const std::vector<NetworkContact>& pairs,
                     long first_image) {
  LineNodes l;
  l.nodes.reserve(2 * pairs.size());
  for (const NetworkContact& c : pairs) {
    l.nodes.push_back(c.a);
    if (c.shift.isZero(0.0)) {
      l.nodes.push_back(c.b);
    } else {
      l.nodes.push_back(first_image + static_cast<std::int64_t>(l.position.size()));
      l.position.push_back(grains.store.x[grains.index(c.b)] + c.shift);
    }
  }
  return l;
}

LineNodes line_nodes(const ParticleStore& p, const std::vector<NetworkContact>& pairs) {
  LineNodes l = line_nodes(NetworkGrains{p, 0, p.size()}, pairs, static_cast<long>(p.size()));
  l.position.insert(l.position.begin(), p.x.begin(), p.x.end());
  return l;
}

NetworkInfo write_force_network(MPI_Comm comm, const std::filesystem::path& path, const NetworkGrains& grains,
                                long total_grains, const std::vector<NetworkContact>& contacts, double time,
                                long step) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<NetworkContact> pairs, walls;
  for (const NetworkContact& c : contacts) (c.wall < 0 ? pairs : walls).push_back(c);
  // Where this rank's pairs, wall contacts and image nodes go: after those of the ranks before it.
  // The image nodes are known once the pairs' rows are (line_nodes), so the counts go around
  // once for all three.
  const LineNodes local = line_nodes(grains, pairs, 0);
  const long mine[3] = {static_cast<long>(pairs.size()), static_cast<long>(walls.size()),
                        static_cast<long>(local.position.size())};
  std::vector<long> counts(3 * static_cast<std::size_t>(size));
  MPI_Allgather(mine, 3, MPI_LONG, counts.data(), 3, MPI_LONG, comm);
  long before[3] = {0, 0, 0}, total[3] = {0, 0, 0};
  for (int r = 0; r < size; ++r)
    for (int k = 0; k < 3; ++k) {
      const long c = counts[3 * static_cast<std::size_t>(r) + static_cast<std::size_t>(k)];
      if (r < rank) before[k] += c;
      total[k] += c;
    }
  LineNodes l = line_nodes(grains, pairs, total_grains + before[2]);
  const auto n = static_cast<hsize_t>(total_grains);
  const auto pair_rows = static_cast<hsize_t>(total[0]);
  const auto node_rows = static_cast<hsize_t>(total_grains + total[2]);
  // The disk reserved before HDF5 writes: the grains twice (their positions and the lines' nodes),
  // the pairs' 17 numbers and 2 nodes, the wall contacts' 16 numbers, the images, the metadata.
  constexpr std::size_t kMetadataBytes = 64 * 1024;
  const std::size_t bytes =
      8 * (6 * static_cast<std::size_t>(total_grains) + 19 * pair_rows +
           16 * static_cast<std::size_t>(total[1]) + 3 * static_cast<std::size_t>(total[2])) +
      kMetadataBytes;
  hdf5::write_shared_file(comm, path, bytes, [&](hid_t file) {
    write_attribute(file, "time", time);
    write_attribute(file, "step", static_cast<double>(step));
    write_attribute(file, "units", "SI: m, N");
    write_attribute(file, "sign_convention",
                    "forces on the first particle of each pair (on the particle at a wall); normal from the "
                    "first to the second (into the wall); overlap > 0 in contact");
    // This rank's rows of the grains' positions, then its image nodes.
    std::vector<double> x(3 * (grains.rows + l.position.size()));
    for (std::size_t i = 0; i < grains.rows; ++i)
      for (int d = 0; d < 3; ++d) x[3 * i + d] = grains.store.x[i][d];
    Handle parts(hdf5::create_group(file, "particles"), H5Gclose, "create group particles");
    const auto first = static_cast<hsize_t>(grains.first_row);
    hdf5::write_rows(comm, parts, "position", x.data(), n, 3, first, grains.rows);
    write_contacts(file, "contacts", pairs, true, {comm, pair_rows, static_cast<hsize_t>(before[0])});
    write_contacts(file, "wall_contacts", walls, false,
                   {comm, static_cast<hsize_t>(total[1]), static_cast<hsize_t>(before[1])});
    Handle lines(hdf5::create_group(file, "lines"), H5Gclose, "create group lines");
    const std::vector<double> images = flatten(l.position);
    std::copy(images.begin(), images.end(), x.begin() + static_cast<std::ptrdiff_t>(3 * grains.rows));
    hdf5::write_row_blocks(comm, lines, "position", x.data(),
                           {H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, node_rows, 3},
                           {{first, grains.rows},
                            {n + static_cast<hsize_t>(before[2]), static_cast<hsize_t>(l.position.size())}});
    hdf5::write_rows(comm, lines, "nodes", l.nodes.data(), pair_rows, 2, static_cast<hsize_t>(before[0]),
                     pairs.size());
  });
  return {path.filename().string(), time, step, total_grains, total[0], static_cast<long>(node_rows)};
}

NetworkInfo write_force_network(const std::filesystem::path& path, const ParticleStore& p,
                                const std::vector<NetworkContact>& contacts, double time, long step) {
  return write_force_network(MPI_COMM_SELF, path, NetworkGrains{p, 0, p.size()}, static_cast<long>(p.size()),
                             contacts, time, step);
}

void write_force_network_xdmf(const std::filesystem::path& path, const std::vector<NetworkInfo>& files) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"force_network\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const NetworkInfo& f : files) {
    const std::string h5 = "force_network/" + f.file + ":/";
    auto item = [&](const std::string& name, long rows, int cols, const char* type = "Float") {
      std::ostringstream i;
      i << "<DataItem Dimensions=\"" << rows;
      if (cols > 1) i << " " << cols;
      i << "\" NumberType=\"" << type << "\" Precision=\"8\" Format=\"HDF\">" << h5 << name << "</DataItem>";
      return i.str();
    };
    auto cell = [&](const char* name, const char* kind, int cols) {
      return std::string("    <Attribute Name=\"") + name + "\" AttributeType=\"" + kind +
             "\" Center=\"Cell\">" + item(std::string("contacts/") + name, f.pairs, cols) + "</Attribute>\n";
    };
    // A file written before /lines existed is drawn between the wrapped centres, as then.
    const bool lines = f.line_nodes >= 0;
    x << "   <Grid Name=\"step_" << f.step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << f.time << "\"/>\n"
      << "    <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\"" << f.pairs
      << "\">" << item(lines ? "lines/nodes" : "contacts/ids", f.pairs, 2, "Int") << "</Topology>\n"
      << "    <Geometry GeometryType=\"XYZ\">"
      << item(lines ? "lines/position" : "particles/position", lines ? f.line_nodes : f.particles, 3)
      << "</Geometry>\n"
      << cell("normal_force_magnitude", "Scalar", 1) << cell("tangential_force_magnitude", "Scalar", 1)
      << cell("overlap", "Scalar", 1) << cell("normal_force", "Vector", 3)
      << cell("tangential_force", "Vector", 3) << cell("normal", "Vector", 3);
    if (lines) x << cell("branch", "Vector", 3);
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  write_text_atomically(path, x.str());
}

void ForceNetworkRecorder::write(const NetworkGrains& grains, long total_grains,
                                 const std::vector<PlaneWall>& walls,
                                 const std::vector<ContactRecord>& records, const PeriodicCell& cell,
                                 double time, long step) {
  // Errors end the write on every rank together, in the line of the rank that found them.
  run_on_root(comm_, [&] { create_folder(folder_ / "force_network"); });
  std::vector<NetworkContact> contacts;
  std::string error;
  try {
    contacts = force_network(grains, walls, records, cell);
  } catch (const std::exception& e) {
    error = e.what();
  }
  throw_if_any(comm_, error);
  char name[64];
  std::snprintf(name, sizeof name, "contacts_%09ld.h5", step);
  const NetworkInfo info = write_force_network(comm_, folder_ / "force_network" / name, grains, total_grains,
                                               contacts, time, step);
  run_on_root(comm_, [&] {
    files_.push_back(info);
    write_force_network_xdmf(folder_ / "force_network.xdmf", files_);
  });
}

void ForceNetworkRecorder::resume() {
  files_.clear();
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(folder_ / "force_network", ec)) {
    if (e.path().extension() != ".h5") continue;
    hdf5::QuietHdf5 quiet;
    const hdf5::Reader r(e.path(), "force-network file");
    files_.push_back({e.path().filename().string(), r.attribute("time"), r.whole_attribute("step"),
                      static_cast<long>(r.rows("/particles/position")),
                      static_cast<long>(r.rows("/contacts/ids")),
                      r.exists("/lines/position") ? static_cast<long>(r.rows("/lines/position")) : -1});
  }
  std::sort(files_.begin(), files_.end(),
            [](const NetworkInfo& a, const NetworkInfo& b) { return a.step < b.step; });
  if (!files_.empty()) write_force_network_xdmf(folder_ / "force_network.xdmf", files_);
}

}  // namespace upgrain::dem::io
