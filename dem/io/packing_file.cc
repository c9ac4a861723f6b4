#include "dem/io/packing_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <sstream>

#include "dem/core/error.h"
#include "dem/io/file_kind.h"
#include "dem/io/hdf5_reader.h"

namespace upgrain::dem::io {

namespace {

// An Upgrain snapshot (dem/io/hdf5_snapshot.h): ids, positions, velocities, angular velocities,
// and for a scene with ellipsoids their semi-axes and orientations.
std::vector<PackedGrain> read_snapshot(const std::filesystem::path& path) {
  hdf5::QuietHdf5 quiet;
  const hdf5::Reader file(path, "packing (Upgrain snapshot)");
  const std::vector<std::int64_t> id = file.read_all<std::int64_t>("/particles/id");
  const hsize_t n = id.size();
  const std::vector<double> radius = file.read<double>("/particles/radius", H5T_NATIVE_DOUBLE, n);
  const std::vector<double> x = file.read<double>("/particles/position", H5T_NATIVE_DOUBLE, n, 3);
  const std::vector<double> v = file.read<double>("/particles/velocity", H5T_NATIVE_DOUBLE, n, 3);
  const std::vector<double> w = file.read<double>("/particles/angular_velocity", H5T_NATIVE_DOUBLE, n, 3);
  const bool shapes = file.exists("/particles/semi_axes");
  std::vector<double> axes, quat;
  if (shapes) {
    axes = file.read<double>("/particles/semi_axes", H5T_NATIVE_DOUBLE, n, 3);
    quat = file.read<double>("/particles/orientation", H5T_NATIVE_DOUBLE, n, 4);
  }
  std::vector<PackedGrain> out(n);
  for (hsize_t k = 0; k < n; ++k) {
    PackedGrain& g = out[k];
    g.file_id = static_cast<long>(id[k]);
    g.line = static_cast<long>(k) + 1;
    g.x = Vec3(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
    g.v = Vec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    g.omega = Vec3(w[3 * k], w[3 * k + 1], w[3 * k + 2]);
    g.semi_axes = shapes ? Vec3(axes[3 * k], axes[3 * k + 1], axes[3 * k + 2]) : Vec3::Constant(radius[k]);
    if (shapes)
      g.orientation = Eigen::Quaterniond(quat[4 * k], quat[4 * k + 1], quat[4 * k + 2], quat[4 * k + 3]);
  }
  return out;
}

// The path names a regular file that reads: anything else is refused with what it is, before
// a reader opens it (a FIFO's open() waits for a writer, /dev/zero never ends; /proc/self/mem is
// a regular file whose first read fails).
void check_readable(const std::filesystem::path& path) {
  const std::string name = "packing " + path.string() + ": ";
  const PathKind kind = path_kind(path.string());
  if (!kind.exists)
    throw Error(name + (kind.description == "does not exist" ? "no such file" : kind.description) +
                " (Particles/initial packing)");
  if (!kind.regular()) throw Error(name + "is " + kind.description + ", not a packing file");
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error(name + "cannot open the file: " + std::strerror(errno));
  char byte = 0;
  ssize_t got = -1;
  do {
    got = ::read(fd, &byte, 1);
  } while (got < 0 && errno == EINTR);
  const int e = errno;
  ::close(fd);
  if (got < 0) throw Error(name + "cannot read the file: " + std::strerror(e));
}

}  // namespace

std::string Packing::name(std::size_t k) const {
  return "grain " + std::to_string(file_id[k]) + " (" + where_word + " " + std::to_string(line[k]) + ")";
}

Packing number_grains(std::vector<PackedGrain> grains, double density, const std::string& file,
                      const std::string& where_word) {
  if (grains.empty()) throw Error("packing " + file + ": holds no grains");
  std::stable_sort(grains.begin(), grains.end(),
                   [](const PackedGrain& a, const PackedGrain& b) { return a.file_id < b.file_id; });
  Packing p;
  p.where_word = where_word;
  p.grains.reserve(grains.size());
  auto at = [&](const PackedGrain& g) {
    return "packing " + file + ", grain " + std::to_string(g.file_id) + " (" + where_word + " " +
           std::to_string(g.line) + "): ";
  };
  for (std::size_t k = 0; k < grains.size(); ++k) {
    const PackedGrain& g = grains[k];
    if (k > 0 && grains[k - 1].file_id == g.file_id)
      throw Error(at(g) + "the id is given twice (also at " + where_word + " " +
                  std::to_string(grains[k - 1].line) + ")");
    const Vec3& ax = g.semi_axes;
    if (!g.x.allFinite() || !g.v.allFinite() || !g.omega.allFinite() || !ax.allFinite())
      throw Error(at(g) + "a value is not finite");
    std::ostringstream m;
    m.precision(17);
    if (!(ax.z() > 0.0) || ax.y() < ax.z() || ax.x() < ax.y()) {
      m << at(g) << "the semi-axes must satisfy a >= b >= c > 0 (a radius must be positive), got " << ax.x()
        << ", " << ax.y() << ", " << ax.z();
      throw Error(m.str());
    }
    const GlobalId id = static_cast<GlobalId>(k);
    if (ax.x() == ax.z()) {
      p.grains.add_sphere(id, ax.x(), density, g.x, g.v, g.omega);
    } else {
      // Text files round a unit quaternion to their digits: renormalised when within 1e-6.
      const double norm = g.orientation.norm();
      if (!(std::abs(norm - 1.0) <= 1e-6)) {
        m << at(g) << "the orientation (w, x, y, z) has norm " << norm << "; give a unit quaternion";
        throw Error(m.str());
      }
      p.grains.add_ellipsoid(id, {ax, density, g.orientation.normalized()}, {g.x, g.v, g.omega});
    }
    p.grains.image.back() = g.image;
    p.file_id.push_back(g.file_id);
    p.line.push_back(g.line);
  }
  return p;
}

Packing read_packing(const std::filesystem::path& path, double density) {
  check_readable(path);
  Packing p;
  std::vector<std::string> notes;
  bool hdf5 = false;
  {
    // The probe of a file that is not HDF5 fails inside the library, which would print its
    // error stack.
    hdf5::QuietHdf5 quiet;
    hdf5 = H5Fis_hdf5(path.c_str()) > 0;
  }
  if (hdf5) {
    p = number_grains(read_snapshot(path), density, path.string(), "row");
    p.format = "Upgrain snapshot";
  } else if (looks_like_lammps_data(path)) {
    std::string style;
    std::optional<Box> box;
    std::array<long, 3> box_line{0, 0, 0};
    p = number_grains(read_lammps_data(path, density, notes, style, &box, &box_line), density, path.string(),
                      "line");
    p.file_box = box;
    p.box_line = box_line;
    p.format = "LAMMPS data file (atom_style " + style + ")";
  } else {
    p = number_grains(read_text_table(path), density, path.string(), "line");
    p.format = "text table";
  }
  p.notes = std::move(notes);
  return p;
}

}  // namespace upgrain::dem::io
