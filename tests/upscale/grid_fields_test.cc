// Grid fields from a grid-stress result in memory and from the HDF5 file the DEM writes:
// the same names and bit-identical values both ways; errors name the field, file or dataset.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <unistd.h>
#include <filesystem>
#include <random>

#include "dem/core/error.h"
#include "dem/io/grid_stress_output.h"
#include "upscale/grid_fields.h"

using namespace upgrain;
namespace fs = std::filesystem;

namespace {

// A per-process folder: these tests do not communicate, each rank writes its own files.
struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("upgrain_upscale_fields_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
};

// A 3 x 2 x 4 grid with random full tensors for every formula and arbitrary counts.
struct StressCase {
  dem::RegularGrid grid;
  dem::GridStress stress;
  StressCase() {
    grid.lo = dem::Vec3(-0.1, 0.0, 0.02);
    grid.hi = dem::Vec3(0.2, 0.05, 0.3);
    grid.n[0] = 3;
    grid.n[1] = 2;
    grid.n[2] = 4;
    const int cells = grid.num_cells();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e4, 1e4);
    for (auto& s : stress.sigma) {
      s.resize(cells);
      for (auto& m : s)
        for (int e = 0; e < 9; ++e) m(e / 3, e % 3) = u(rng);
    }
    for (int c = 0; c < cells; ++c) {
      stress.particles.push_back(10 + c);
      stress.internal_contacts.push_back(3 * c);
      stress.external_contacts.push_back(100 - c);
      stress.wall_contacts.push_back(c % 3);
      stress.solid_fraction.push_back(0.5 + 0.01 * c);
    }
    stress.cell_volume = grid.cell_volume();
  }
};

}  // namespace

TEST(GridFields, AddChecksSizeAndLookupListsFields) {
  upscale::GridFields g;
  g.n = {2, 3, 1};
  g.add("a", std::vector<double>(6, 1.0));
  try {
    g.add("too_short", std::vector<double>(5));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("too_short"), std::string::npos) << e.what();
  }
  EXPECT_THROW(g.add("a", std::vector<double>(6)), Error);
  EXPECT_EQ(g["a"][5], 1.0);
  try {
    (void)g["b"];
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("b;"), std::string::npos) << m;
    EXPECT_NE(m.find("there are: a"), std::string::npos) << m;
  }
}

TEST(GridFields, FromStressNamesAndValues) {
  const StressCase s;
  using F = dem::StressFormula;
  const auto g = upscale::grid_fields_from_stress(s.grid, s.stress, {F::modified_nicot, F::bagi});
  ASSERT_EQ(g.names.size(), 2u * 10 + 5);
  EXPECT_EQ(g.names[0], "modified_nicot_s_xx");
  EXPECT_EQ(g.names[1], "modified_nicot_s_xy");
  EXPECT_EQ(g.names[8], "modified_nicot_s_zz");
  EXPECT_EQ(g.names[9], "modified_nicot_rai");
  EXPECT_EQ(g.names[10], "bagi_s_xx");
  EXPECT_EQ(g.names[20], "particles");
  EXPECT_EQ(g.names[24], "solid_fraction");
  EXPECT_EQ(g.n, (std::array<int, 3>{3, 2, 4}));
  EXPECT_EQ(g.lo[2], 0.02);
  for (int c = 0; c < g.num_cells(); ++c) {
    EXPECT_EQ(g["bagi_s_xz"][c], s.stress[F::bagi][c](0, 2));
    EXPECT_EQ(g["bagi_s_zx"][c], s.stress[F::bagi][c](2, 0));
    EXPECT_EQ(g["modified_nicot_s_zy"][c], s.stress[F::modified_nicot][c](2, 1));
    EXPECT_EQ(g["external_contacts"][c], 100 - c);
  }
}

TEST(GridFields, FileRoundTripIsExact) {
  const StressCase s;
  const Scratch scratch;
  using F = dem::StressFormula;
  // Deliberately not in enum order: the file lists its groups by name, the reader restores
  // the enum order, and values are compared by name.
  const std::vector<F> formulas = {F::weber, F::modified_de_saxce, F::bagi};
  const fs::path path = scratch.dir / "grid_stress_000000042.h5";
  dem::io::write_grid_stress(path, s.grid, s.stress, formulas, 0.125, 42);
  const auto memory = upscale::grid_fields_from_stress(s.grid, s.stress, formulas);
  const auto file = upscale::read_grid_fields(path);
  EXPECT_EQ(file.n, memory.n);
  EXPECT_EQ(file.lo, memory.lo);
  EXPECT_EQ(file.hi, memory.hi);
  EXPECT_EQ(file.time, 0.125);
  EXPECT_EQ(file.step, 42);
  ASSERT_EQ(file.names.size(), memory.names.size());
  EXPECT_EQ(file.names[0], "weber_s_xx");
  EXPECT_EQ(file.names[10], "bagi_s_xx");
  EXPECT_EQ(file.names[20], "modified_de_saxce_s_xx");
  for (std::size_t k = 0; k < memory.names.size(); ++k) EXPECT_EQ(file[memory.names[k]], memory.values[k]);
}

TEST(GridFields, MissingFileAndDatasetAreNamed) {
  const Scratch scratch;
  const fs::path missing = scratch.dir / "nothing_here.h5";
  try {
    (void)upscale::read_grid_fields(missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }

  const StressCase s;
  const fs::path path = scratch.dir / "damaged.h5";
  dem::io::write_grid_stress(path, s.grid, s.stress, {dem::StressFormula::bagi}, 0.0, 0);
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GE(H5Ldelete(f, "/stress/bagi/rai", H5P_DEFAULT), 0);
    H5Fclose(f);
  }
  try {
    (void)upscale::read_grid_fields(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path.string()), std::string::npos) << m;
    EXPECT_NE(m.find("/stress/bagi/rai"), std::string::npos) << m;
  }
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GE(H5Ldelete(f, "/cells", H5P_DEFAULT), 0);
    ASSERT_GE(H5Ldelete(f, "/stress/bagi", H5P_DEFAULT), 0);
    H5Fclose(f);
  }
  try {
    (void)upscale::read_grid_fields(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/cells/particles"), std::string::npos) << e.what();
  }
}
