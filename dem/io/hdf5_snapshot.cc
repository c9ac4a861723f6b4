#include "dem/io/hdf5_snapshot.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <sstream>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/io/hdf5_util.h"
#include "dem/shape/grain_shapes.h"

namespace upgrain::dem::io {

namespace {

using hdf5::Handle;
using hdf5::write_attribute;
using hdf5::write_rows;

std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out(3 * v.size());
  for (std::size_t k = 0; k < v.size(); ++k)
    for (int d = 0; d < 3; ++d) out[3 * k + d] = v[k][d];
  return out;
}

}  // namespace

void write_snapshot(MPI_Comm comm, const std::filesystem::path& path, const ParticleStore& p,
                    const SnapshotRows& where, const std::vector<PlaneWall>& walls,
                    const std::vector<Vec3>& wall_force, double time, long step) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::size_t n = p.size();
  const auto total = static_cast<hsize_t>(where.total);
  const auto first = static_cast<hsize_t>(where.first);
  const bool images = where.images, shapes = where.shapes;
  // This rank's rows of a data set of `cols` columns.
  auto rows = [&](hid_t group, const char* name, const auto* data, hsize_t cols) {
    write_rows(comm, group, name, data, total, cols, first, n);
  };
  // The disk reserved before HDF5 writes: the rows, the walls and the metadata (a few kB;
  // kMetadataBytes is well above what it takes).
  constexpr std::size_t kMetadataBytes = 64 * 1024;
  const std::size_t columns =
      1 + 1 + 4 * 3 + (images ? 3 : 0) + (shapes ? 3 * shapes::description_columns().size() + 4 + 9 : 0);
  const std::size_t bytes =
      static_cast<std::size_t>(total) * 8 * columns + walls.size() * 8 * 10 + kMetadataBytes;
  hdf5::write_shared_file(comm, path, bytes, [&](hid_t file) {
    write_attribute(file, "time", time);
    write_attribute(file, "step", static_cast<double>(step));
    write_attribute(file, "units", "SI: m, s, kg, N");
    write_attribute(file, "frame", "right-handed, z up, gravity along -z");

    Handle parts(hdf5::create_group(file, "particles"), H5Gclose, "create group particles");
    std::vector<std::int64_t> ids(p.id.begin(), p.id.end());
    rows(parts, "id", ids.data(), 1);
    rows(parts, "radius", p.radius.data(), 1);
    const struct {
      const char* name;
      const std::vector<Vec3>* data;
    } vectors[] = {
        {"position", &p.x}, {"velocity", &p.v}, {"angular_velocity", &p.omega}, {"force", &p.force}};
    for (const auto& f : vectors) rows(parts, f.name, flatten(*f.data).data(), 3);
    if (images) {
      std::vector<std::int32_t> image(3 * n);
      for (std::size_t k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) image[3 * k + d] = p.image[k][d];
      rows(parts, "image", image.data(), 3);
    }
    // A store without shapes on this rank (no grains here) writes its empty share as well.
    if (shapes) {
      for (const shapes::DescriptionColumn& c : shapes::description_columns())
        rows(parts, c.name, flatten(p.*c.values).data(), 3);
      std::vector<double> quat(4 * n), tensor(9 * n);
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Quaterniond& q = p.orientation[k];
        quat[4 * k] = q.w();
        quat[4 * k + 1] = q.x();
        quat[4 * k + 2] = q.y();
        quat[4 * k + 3] = q.z();
        const Mat3 r = q.toRotationMatrix();
        const Mat3 t = r * p.semi_axes[k].asDiagonal() * r.transpose();
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) tensor[9 * k + 3 * a + b] = t(a, b);
      }
      rows(parts, "orientation", quat.data(), 4);
      rows(parts, "shape_tensor", tensor.data(), 9);
    }

    // The walls: the same on every rank, written by rank 0.
    Handle wg(hdf5::create_group(file, "walls"), H5Gclose, "create group walls");
    const std::size_t nw = walls.size();
    std::vector<double> point(3 * nw), normal(3 * nw), force(3 * nw, 0.0), friction(nw);
    std::string names;
    for (std::size_t w = 0; w < nw; ++w) {
      for (int d = 0; d < 3; ++d) {
        point[3 * w + d] = walls[w].point[d];
        normal[3 * w + d] = walls[w].normal[d];
        if (w < wall_force.size()) force[3 * w + d] = wall_force[w][d];
      }
      friction[w] = walls[w].friction;
      names += (w ? "," : "") + walls[w].name;
    }
    write_attribute(wg, "names", names);
    const hsize_t wall_rows = rank == 0 ? nw : 0;
    write_rows(comm, wg, "point", point.data(), nw, 3, 0, wall_rows);
    write_rows(comm, wg, "normal", normal.data(), nw, 3, 0, wall_rows);
    write_rows(comm, wg, "friction", friction.data(), nw, 1, 0, wall_rows);
    write_rows(comm, wg, "force", force.data(), nw, 3, 0, wall_rows);
  });
}

void write_snapshot(const std::filesystem::path& path, const ParticleStore& p,
                    const std::vector<PlaneWall>& walls, const std::vector<Vec3>& wall_force, double time,
                    long step, bool images) {
  std::vector<int> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return p.id[a] < p.id[b]; });
  ParticleStore sorted = p;
  sorted.permute(order);
  write_snapshot(MPI_COMM_SELF, path, sorted, {0, static_cast<long>(p.size()), images, p.has_shapes()}, walls,
                 wall_force, time, step);
}

void write_xdmf(const std::filesystem::path& path, const std::vector<SnapshotInfo>& snaps) {
  std::ostringstream x;
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const SnapshotInfo& s : snaps) {
    const std::string h5 = s.file + ":/particles/";
    auto item = [&](const char* name, int cols) {
      std::ostringstream i;
      i << "<DataItem Dimensions=\"" << s.count;
      if (cols > 1) i << " " << cols;
      i << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << name << "</DataItem>";
      return i.str();
    };
    x << "   <Grid Name=\"step_" << s.step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << s.time << "\"/>\n"
      << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << s.count << "\"/>\n"
      << "    <Geometry GeometryType=\"XYZ\">" << item("position", 3) << "</Geometry>\n"
      << "    <Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\"><DataItem Dimensions=\""
      << s.count << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << h5
      << "id</DataItem></Attribute>\n"
      << "    <Attribute Name=\"radius\" AttributeType=\"Scalar\" Center=\"Node\">" << item("radius", 1)
      << "</Attribute>\n"
      << "    <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">" << item("velocity", 3)
      << "</Attribute>\n"
      << "    <Attribute Name=\"angular_velocity\" AttributeType=\"Vector\" Center=\"Node\">"
      << item("angular_velocity", 3) << "</Attribute>\n"
      << "    <Attribute Name=\"force\" AttributeType=\"Vector\" Center=\"Node\">" << item("force", 3)
      << "</Attribute>\n";
    if (s.shapes) {
      x << "    <Attribute Name=\"shape_tensor\" AttributeType=\"Tensor\" Center=\"Node\">"
        << item("shape_tensor", 9) << "</Attribute>\n";
      for (const shapes::DescriptionColumn& c : shapes::description_columns())
        x << "    <Attribute Name=\"" << c.name << "\" AttributeType=\"Vector\" Center=\"Node\">"
          << item(c.name, 3) << "</Attribute>\n";
    }
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  write_text_atomically(path, x.str());
}

}  // namespace upgrain::dem::io
