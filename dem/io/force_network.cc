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

namespace upgrain::dem::io {

namespace {

using hdf5::Handle;
using hdf5::write_attribute;
using hdf5::write_dataset;

void split_force(NetworkContact& c, const Vec3& force) {
  c.normal_force = force.dot(c.normal) * c.normal;
  c.tangential_force = force - c.normal_force;
}

void write_vectors(hid_t group, const char* name, const std::vector<NetworkContact>& cs,
                   Vec3 NetworkContact::*field) {
  std::vector<double> flat(3 * cs.size());
  for (std::size_t k = 0; k < cs.size(); ++k)
    for (int d = 0; d < 3; ++d) flat[3 * k + d] = (cs[k].*field)[d];
  write_dataset(group, name, flat.data(), cs.size(), 3);
}

void write_contacts(hid_t file, const char* group_name, const std::vector<NetworkContact>& cs, bool pairs) {
  Handle g(hdf5::create_group(file, group_name), H5Gclose, std::string("create group ") + group_name);
  const std::size_t m = cs.size();
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
    write_dataset(g, "ids", second.data(), m, 2);
  } else {
    write_dataset(g, "particle", first.data(), m, 1);
    write_dataset(g, "wall", second.data(), m, 1);
  }
  write_vectors(g, "point", cs, &NetworkContact::point);
  write_vectors(g, "normal", cs, &NetworkContact::normal);
  if (pairs) write_vectors(g, "branch", cs, &NetworkContact::branch);
  write_vectors(g, "normal_force", cs, &NetworkContact::normal_force);
  write_vectors(g, "tangential_force", cs, &NetworkContact::tangential_force);
  write_dataset(g, "overlap", overlap.data(), m, 1);
  write_dataset(g, "normal_force_magnitude", fn.data(), m, 1);
  write_dataset(g, "tangential_force_magnitude", ft.data(), m, 1);
}

}  // namespace

std::vector<NetworkContact> force_network(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                                          const std::vector<ContactRecord>& records,
                                          const PeriodicCell& cell) {
  std::vector<NetworkContact> out;
  out.reserve(records.size());
  ContactSolverStats stats;
  for (const ContactRecord& r : records) {
    const auto a = static_cast<std::size_t>(r.a);
    if (a >= p.size() || p.id[a] != r.a) throw Error("force network: the state is not sorted by id");
    NetworkContact c;
    c.a = r.a;
    c.point = get(r.point);
    if (r.b >= 0) {
      const auto b = static_cast<std::size_t>(r.b);
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

LineNodes line_nodes(const ParticleStore& p, const std::vector<NetworkContact>& pairs) {
  LineNodes l;
  l.position = p.x;
  l.nodes.reserve(2 * pairs.size());
  for (const NetworkContact& c : pairs) {
    l.nodes.push_back(c.a);
    if (c.shift.isZero(0.0)) {
      l.nodes.push_back(c.b);
    } else {
      l.nodes.push_back(static_cast<std::int64_t>(l.position.size()));
      l.position.push_back(p.x[static_cast<std::size_t>(c.b)] + c.shift);
    }
  }
  return l;
}

NetworkInfo write_force_network(const std::filesystem::path& path, const ParticleStore& p,
                                const std::vector<NetworkContact>& contacts, double time, long step) {
  std::vector<NetworkContact> pairs, walls;
  for (const NetworkContact& c : contacts) (c.wall < 0 ? pairs : walls).push_back(c);
  AtomicFile target(path);
  long nodes = 0;
  {
    Handle file(hdf5::create_file(target.temporary_path()), H5Fclose, "create " + path.string());
    write_attribute(file, "time", time);
    write_attribute(file, "step", static_cast<double>(step));
    write_attribute(file, "units", "SI: m, N");
    write_attribute(file, "sign_convention",
                    "forces on the first particle of each pair (on the particle at a wall); normal from the "
                    "first to the second (into the wall); overlap > 0 in contact");
    Handle parts(hdf5::create_group(file, "particles"), H5Gclose, "create group particles");
    std::vector<double> x(3 * p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int d = 0; d < 3; ++d) x[3 * i + d] = p.x[i][d];
    write_dataset(parts, "position", x.data(), p.size(), 3);
    write_contacts(file, "contacts", pairs, true);
    write_contacts(file, "wall_contacts", walls, false);
    Handle lines(hdf5::create_group(file, "lines"), H5Gclose, "create group lines");
    const LineNodes l = line_nodes(p, pairs);
    hdf5::write_vectors(lines, "position", l.position);
    write_dataset(lines, "nodes", l.nodes.data(), pairs.size(), 2);
    nodes = static_cast<long>(l.position.size());
    hdf5::flush(file, target.final_path().string());
  }
  target.commit();
  return {path.filename().string(),        time, step, static_cast<long>(p.size()),
          static_cast<long>(pairs.size()), nodes};
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

void ForceNetworkRecorder::write(const ParticleStore& p, const std::vector<PlaneWall>& walls,
                                 const std::vector<ContactRecord>& records, const PeriodicCell& cell,
                                 double time, long step) {
  create_folder(folder_ / "force_network");
  char name[64];
  std::snprintf(name, sizeof name, "contacts_%09ld.h5", step);
  files_.push_back(write_force_network(folder_ / "force_network" / name, p,
                                       force_network(p, walls, records, cell), time, step));
  write_force_network_xdmf(folder_ / "force_network.xdmf", files_);
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
