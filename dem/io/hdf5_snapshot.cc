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
using hdf5::write_dataset;

std::vector<double> flatten(const std::vector<Vec3>& v, const std::vector<std::size_t>& order) {
  std::vector<double> out(3 * order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    for (int d = 0; d < 3; ++d) out[3 * k + d] = v[order[k]][d];
  return out;
}

}  // namespace

void write_snapshot(const std::filesystem::path& path, const ParticleStore& p,
                    const std::vector<PlaneWall>& walls, const std::vector<Vec3>& wall_force, double time,
                    long step, bool images) {
  const std::size_t n = p.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });

  AtomicFile target(path);
  {
    Handle file(hdf5::create_file(target.temporary_path()), H5Fclose,
                "create " + target.temporary_path().string());
    write_attribute(file, "time", time);
    write_attribute(file, "step", static_cast<double>(step));
    write_attribute(file, "units", "SI: m, s, kg, N");
    write_attribute(file, "frame", "right-handed, z up, gravity along -z");

    Handle parts(hdf5::create_group(file, "particles"), H5Gclose, "create group particles");
    std::vector<std::int64_t> ids(n);
    std::vector<double> radius(n);
    for (std::size_t k = 0; k < n; ++k) {
      ids[k] = p.id[order[k]];
      radius[k] = p.radius[order[k]];
    }
    write_dataset(parts, "id", ids.data(), n, 1);
    write_dataset(parts, "radius", radius.data(), n, 1);
    const struct {
      const char* name;
      const std::vector<Vec3>* data;
    } vectors[] = {
        {"position", &p.x}, {"velocity", &p.v}, {"angular_velocity", &p.omega}, {"force", &p.force}};
    for (const auto& f : vectors) {
      const std::vector<double> flat = flatten(*f.data, order);
      write_dataset(parts, f.name, flat.data(), n, 3);
    }
    if (images) {
      std::vector<std::int32_t> image(3 * n);
      for (std::size_t k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) image[3 * k + d] = p.image[order[k]][d];
      write_dataset(parts, "image", image.data(), n, 3);
    }
    if (p.has_shapes()) {
      for (const shapes::DescriptionColumn& c : shapes::description_columns()) {
        const std::vector<double> flat = flatten(p.*c.values, order);
        write_dataset(parts, c.name, flat.data(), n, 3);
      }
      std::vector<double> quat(4 * n), tensor(9 * n);
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Quaterniond& q = p.orientation[order[k]];
        quat[4 * k] = q.w();
        quat[4 * k + 1] = q.x();
        quat[4 * k + 2] = q.y();
        quat[4 * k + 3] = q.z();
        const Mat3 r = q.toRotationMatrix();
        const Mat3 t = r * p.semi_axes[order[k]].asDiagonal() * r.transpose();
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) tensor[9 * k + 3 * a + b] = t(a, b);
      }
      write_dataset(parts, "orientation", quat.data(), n, 4);
      write_dataset(parts, "shape_tensor", tensor.data(), n, 9);
    }

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
    write_dataset(wg, "point", point.data(), nw, 3);
    write_dataset(wg, "normal", normal.data(), nw, 3);
    write_dataset(wg, "friction", friction.data(), nw, 1);
    write_dataset(wg, "force", force.data(), nw, 3);
    hdf5::flush(file, target.final_path().string());
  }
  target.commit();
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
