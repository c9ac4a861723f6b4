// Initial packings (docs/input.md, "Starting from a packing"): the three formats read to the
// same grains, ids numbered in the order of the file's, and bad files refused with the line,
// column and grains named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>

#include "dem/core/error.h"
#include "dem/io/hdf5_snapshot.h"
#include "dem/io/packing_file.h"

using namespace upgrain::dem;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name, const std::string& text = {}) {
  fs::path d = fs::temp_directory_path() / ("upgrain_packing_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  if (!text.empty()) std::ofstream(d / name) << text;
  return d / name;
}

// The message of the error reading (and checking) `path` throws, or "" if it is accepted.
std::string refusal(const fs::path& path, const BoxContainer& box = {}) {
  try {
    const io::Packing p = io::read_packing(path, 2650.0);
    io::check_packing(p, box, path.string(), io::kPackingOverlapLimit);
  } catch (const upgrain::Error& e) {
    return e.what();
  }
  return "";
}

void expect_refused(const fs::path& path, const std::string& pattern, const BoxContainer& box = {}) {
  const std::string m = refusal(path, box);
  EXPECT_TRUE(std::regex_search(m, std::regex(pattern))) << "message: '" << m << "'\npattern: " << pattern;
}

}  // namespace

TEST(Packing, CsvWithHeaderNumbersGrainsByTheFileIds) {
  // Ids out of order and not from 0; the grain of id 3 is an ellipsoid turned about z.
  const fs::path f = scratch("bed.csv",
                             "# a comment\n"
                             "id, x, y, z, a, b, c, qw, qx, qy, qz, vx, vy, vz\n"
                             "7, 0.010, 0.010, 0.002, 0.0015, 0.0015, 0.0015, 1, 0, 0, 0, 0, 0, -1\n"
                             "3, 0.020, 0.010, 0.002, 0.002, 0.0016, 0.001, 0.70710678118654752, 0, 0, "
                             "0.70710678118654752, 0, 0, 0\n");
  const io::Packing p = io::read_packing(f, 2650.0);
  ASSERT_EQ(p.grains.size(), 2u);
  EXPECT_EQ(p.file_id, (std::vector<long>{3, 7}));
  EXPECT_EQ(p.line, (std::vector<long>{4, 3}));
  EXPECT_EQ(p.grains.id, (std::vector<GlobalId>{0, 1}));
  EXPECT_TRUE(p.grains.is_ellipsoid(0));
  EXPECT_FALSE(p.grains.is_ellipsoid(1));
  EXPECT_EQ(p.grains.x[1], Vec3(0.010, 0.010, 0.002));
  EXPECT_EQ(p.grains.v[1], Vec3(0, 0, -1));
  EXPECT_EQ(p.grains.semi_axes[0], Vec3(0.002, 0.0016, 0.001));
  // Turned by 90 degrees about z: the major axis along y, so the grain reaches b along x.
  EXPECT_NEAR(p.grains.reach(0, Vec3::UnitX()), 0.0016, 1e-15);
  EXPECT_NEAR(p.grains.reach(0, Vec3::UnitY()), 0.002, 1e-15);
  EXPECT_NEAR(p.grains.mass(1), 2650.0 * 4.0 / 3.0 * std::numbers::pi * 0.0015 * 0.0015 * 0.0015, 1e-18);
  EXPECT_EQ(refusal(f), "");
  EXPECT_EQ(p.name(0), "grain 3 (line 4)");
}

TEST(Packing, WhitespaceTableWithoutHeaderAndDiameterColumn) {
  const fs::path plain = scratch("plain.txt", "0 0.01 0.01 0.01 0.001\n\n1 0.02 0.01 0.01 0.002\n");
  const io::Packing p = io::read_packing(plain, 1000.0);
  ASSERT_EQ(p.grains.size(), 2u);
  EXPECT_EQ(p.grains.radius, (std::vector<double>{0.001, 0.002}));
  EXPECT_FALSE(p.grains.has_shapes());
  const fs::path d = scratch("diameter.csv", "x,y,z,d\n0.01,0.01,0.01,0.002\n");
  EXPECT_EQ(io::read_packing(d, 1000.0).grains.radius, (std::vector<double>{0.001}));
}

TEST(Packing, LammpsDataFileWithVelocities) {
  // atom_style sphere: id type diameter density x y z (image flags optional); LAMMPS ids from 1.
  const fs::path f = scratch("bed.data",
                             "LAMMPS data file\n\n2 atoms\n1 atom types\n\n0 0.03 xlo xhi\n0 0.03 ylo yhi\n"
                             "0 0.1 zlo zhi\n\nMasses\n\n1 1.0\n\nAtoms # sphere\n\n"
                             "2 1 0.003 2500 0.02 0.01 0.0015 0 0 0\n1 1 0.002 2500 0.01 0.01 0.001 0 0 0\n\n"
                             "Velocities\n\n2 0.1 0 0 0 0 5\n1 0 0 0 0 0 0\n");
  ASSERT_TRUE(io::looks_like_lammps_data(f));
  const io::Packing p = io::read_packing(f, 2650.0);
  EXPECT_EQ(p.format, "LAMMPS data file (atom_style sphere)");
  ASSERT_EQ(p.grains.size(), 2u);
  EXPECT_EQ(p.file_id, (std::vector<long>{1, 2}));
  EXPECT_EQ(p.grains.radius, (std::vector<double>{0.001, 0.0015}));
  EXPECT_EQ(p.grains.v[1], Vec3(0.1, 0, 0));
  EXPECT_EQ(p.grains.omega[1], Vec3(0, 0, 5));
  // The file's density is not the scene's: said, and the scene's taken.
  ASSERT_EQ(p.notes.size(), 1u);
  EXPECT_NE(p.notes[0].find("density 2500 kg/m^3 differs from Particles/density = 2650"), std::string::npos);
  EXPECT_NEAR(p.grains.mass(0), 2650.0 * 4.0 / 3.0 * std::numbers::pi * 1e-9, 1e-20);
}

TEST(Packing, SnapshotReadsBackBitForBit) {
  ParticleStore s;
  s.add_sphere(0, 0.0015, 2650.0, Vec3(0.0101, 0.0102, 0.0103), Vec3(0.1, 0.2, 0.3), Vec3(1, 2, 3));
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.9, 0.1, 0.3, -0.2).normalized();
  s.add_ellipsoid(1, {Vec3(0.002, 0.0016, 0.0008), 2650.0, q},
                  {Vec3(0.0201, 0.011, 0.0042), Vec3::Zero(), Vec3::Zero()});
  const fs::path f = scratch("particles_0.h5");
  io::write_snapshot(f, s, make_open_box(BoxContainer{}), std::vector<Vec3>(5, Vec3::Zero()), 0.0, 0);
  const io::Packing p = io::read_packing(f, 2650.0);
  EXPECT_EQ(p.format, "Upgrain snapshot");
  ASSERT_EQ(p.grains.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(p.grains.x[i], s.x[i]);
    EXPECT_EQ(p.grains.v[i], s.v[i]);
    EXPECT_EQ(p.grains.omega[i], s.omega[i]);
    EXPECT_EQ(p.grains.semi_axes[i], s.semi_axes[i]);
    EXPECT_EQ(p.grains.inv_mass[i], s.inv_mass[i]);
  }
  EXPECT_EQ(p.grains.orientation[1].coeffs(), s.orientation[1].coeffs());
  EXPECT_EQ(refusal(f), "");
}

TEST(Packing, BadTablesNameLineAndColumn) {
  expect_refused(scratch("unknown.csv", "id,x,y,z,rad\n0,0.01,0.01,0.01,0.001\n"),
                 R"(unknown.csv:1:10: unknown column 'rad' \(known: id, x, y, z, r, radius, d, diameter)");
  expect_refused(scratch("nan.csv", "id,x,y,z,r\n0,0.01,0.01,0.01,0.001\n1, abc,0.01,0.03,0.001\n"),
                 R"(nan.csv:3:4: 'abc' in column 'x' is not a number)");
  expect_refused(scratch("short.txt", "id x y z r\n0 0.01 0.01 0.01\n"),
                 R"(short.txt:2: 4 fields, but the table has 5 columns)");
  expect_refused(scratch("twice.csv", "id,x,y,z,r\n4,0.01,0.01,0.01,0.001\n4,0.03,0.01,0.01,0.001\n"),
                 R"(twice.csv, grain 4 \(line 3\): the id is given twice \(also at line 2\))");
  expect_refused(scratch("size.csv", "id,x,y,z\n0,0.01,0.01,0.01\n"), R"(size.csv:1: give the size once)");
  expect_refused(scratch("axes.csv", "x,y,z,a,b,c\n0.01,0.01,0.01,0.001,0.002,0.001\n"),
                 R"(grain 0 \(line 2\): the semi-axes must satisfy a >= b >= c > 0)");
  expect_refused(scratch("quat.csv", "x,y,z,a,b,c,qw,qx,qy,qz\n0.01,0.01,0.01,0.002,0.001,0.001,1,1,0,0\n"),
                 R"(the orientation \(w, x, y, z\) has norm 1.414)");
  expect_refused(scratch("columns.txt", "0 0.01 0.01 0.01 0.001 7\n"),
                 R"(columns.txt:1: 6 columns and no header line)");
  expect_refused(scratch("empty.csv", "# nothing\n\n"), R"(holds no grains)");
  expect_refused(
      scratch("atomic.data", "title\n\n1 atoms\n\nAtoms # atomic\n\n1 1 0.01 0.01 0.01\n"),
      R"(atomic.data:5: the Atoms section is atom_style 'atomic'; Upgrain reads atom_style sphere or granular)");
  // Image flags on a walled axis (docs/periodic.md): the file, grain, line and axis named.
  expect_refused(
      scratch("image.data", "title\n\n1 atoms\n\nAtoms\n\n1 1 0.002 2650 0.01 0.01 0.01 0 1 0\n"),
      R"(image.data, grain 1 \(line 7\): image flag y = 1, but y is walled \(Container/periodic axes\))");
  expect_refused(scratch("count.data", "title\n\n2 atoms\n\nAtoms\n\n1 1 0.002 2650 0.01 0.01 0.01\n"),
                 R"(the header says 2 atoms, the Atoms section has 1)");
  expect_refused(scratch("missing.csv"), R"(missing.csv: no such file)");
}

TEST(Packing, GrainsOutsideTheContainerOrOverlappingAreRefused) {
  BoxContainer box;  // 0.06 x 0.06 m
  // Through the x+ wall by 0.5 mm.
  expect_refused(
      scratch("out.csv", "id,x,y,z,r\n0,0.03,0.03,0.01,0.001\n1,0.0595,0.03,0.01,0.001\n"),
      R"(out.csv, grain 1 \(line 3\) at \(0.0595, 0.03, 0.01\) m is outside the container: it reaches 0.0005 m through the wall_x_max)",
      box);
  // Below the floor.
  expect_refused(scratch("low.csv", "id,x,y,z,r\n0,0.03,0.03,0.0005,0.001\n"), R"(through the floor)", box);
  // A gate at x = 0.03 holds the grains of a constrained collapse.
  BoxContainer gated = box;
  gated.gate_x = 0.03;
  expect_refused(scratch("gate.csv", "id,x,y,z,r\n0,0.0295,0.03,0.01,0.001\n"),
                 R"(through the gate .*gate x = 0.03)", gated);
  // Two spheres 10 % of a radius into each other; a settled bed's 1 % is taken.
  expect_refused(
      scratch("deep.csv", "id,x,y,z,r\n0,0.03,0.03,0.01,0.001\n1,0.0319,0.03,0.01,0.001\n"),
      R"(grain 0 \(line 2\) and grain 1 \(line 3\) overlap by 0.0001 m, 0.1 of the smaller one's smallest semi-axis)",
      box);
  EXPECT_EQ(
      refusal(scratch("touch.csv", "id,x,y,z,r\n0,0.03,0.03,0.01,0.001\n1,0.03199,0.03,0.01,0.001\n"), box),
      "");
  // Ellipsoids: their bounding spheres overlap, the grains do not (side by side along their
  // short axes, 0.1 mm apart). With one turned towards the other they overlap: by 1.9 mm along y,
  // but the depth is the shortest translation that separates them, which goes up and sideways:
  // min over phi of 0.001 + sqrt(9e-6 cos^2 phi + 1e-6 sin^2 phi) - 0.0021 cos phi = 1.67 mm
  // (phi about 67 degrees from y towards z).
  const std::string apart =
      "id,x,y,z,a,b,c\n0,0.03,0.03,0.01,0.003,0.001,0.001\n1,0.03,0.0321,0.01,0.003,0.001,0.001\n";
  EXPECT_EQ(refusal(scratch("side.csv", apart), box), "");
  expect_refused(
      scratch("turned.csv",
              "id,x,y,z,a,b,c,qw,qx,qy,qz\n0,0.03,0.03,0.01,0.003,0.001,0.001,1,0,0,0\n"
              "1,0.03,0.0321,0.01,0.003,0.001,0.001,0.70710678118654752,0,0,0.70710678118654752\n"),
      R"(grain 0 \(line 2\) and grain 1 \(line 3\) overlap by 0.00167 m)", box);
}

// A LAMMPS data file of a periodic cell (docs/periodic.md): its image flags are kept along the
// periodic axes, and its box must be the cell.
TEST(Packing, LammpsImageFlagsAreKeptAlongPeriodicAxes) {
  const std::string text =
      "LAMMPS data file\n\n2 atoms\n1 atom types\n\n0 0.03 xlo xhi\n0 0.03 ylo yhi\n0 0.1 zlo zhi\n\n"
      "Atoms # sphere\n\n1 1 0.002 2650 0.01 0.01 0.001 2 -1 0\n2 1 0.002 2650 0.02 0.01 0.001 0 0 0\n";
  BoxContainer box;
  box.lx = box.ly = 0.03;
  box.periodic = {true, true, false};
  const fs::path f = scratch("periodic.data", text);
  EXPECT_EQ(refusal(f, box), "");
  const io::Packing p = io::read_packing(f, 2650.0);
  EXPECT_EQ(p.grains.image[0], (ImageCount{2, -1, 0}));
  EXPECT_EQ(p.grains.image[1], (ImageCount{0, 0, 0}));
  // Periodic along x only: the flag along y is refused.
  box.periodic = {true, false, false};
  expect_refused(f, R"(periodic.data, grain 1 \(line 12\): image flag y = -1, but y is walled)", box);
  // A box that is not the cell.
  box.periodic = {true, true, false};
  box.lx = 0.04;
  expect_refused(
      f,
      R"(periodic.data:6: the box along the periodic axis x is \[0, 0.03\] m, and the periodic cell is \[0, 0.04\] m \(Container/length x\))",
      box);
}
