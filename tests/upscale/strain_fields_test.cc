// Grid strain on the deal.II mesh (upscale/strain_fields.h): an affine motion of a random
// packing gives ln J = ln det F and the Hencky components of the map in every valid cell,
// invalid cells are zero with F_valid = 0 and their reason; the fields read from a written
// grid-strain file equal those from memory bit for bit; written through the mesh, the
// cell data read back bit-identical (also on 2 ranks under the mpiexec registration) and
// the VTU names the fields ParaView shows.
#include <gtest/gtest.h>
#include <mpi.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "dem/core/error.h"
#include "upscale/grid_mesh.h"
#include "upscale/strain/grid_strain.h"
#include "upscale/strain/grid_strain_output.h"
#include "upscale/strain/strain_measures.h"
#include "upscale/strain_fields.h"

using namespace upgrain;
namespace fs = std::filesystem;

namespace {

// 3 x 2 x 2 cells; 30 random points per cell except cell 4 (2 points: too few).
upscale::GridStrain sheared_packing(const dem::Mat3& f) {
  dem::RegularGrid grid;
  grid.lo = dem::Vec3(0.2, -0.1, 0.0);
  grid.hi = grid.lo + dem::Vec3(0.06, 0.04, 0.04);
  grid.n[0] = 3;
  grid.n[1] = 2;
  grid.n[2] = 2;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  const dem::Vec3 h(0.02, 0.02, 0.02);
  std::vector<dem::GlobalId> id;
  std::vector<dem::Vec3> x0, x, v;
  for (int c = 0; c < grid.num_cells(); ++c)
    for (int k = 0; k < (c == 4 ? 2 : 30); ++k) {
      x0.push_back(grid.cell_centre(c) - 0.5 * h + dem::Vec3(u(rng), u(rng), u(rng)).cwiseProduct(h));
      id.push_back(static_cast<dem::GlobalId>(id.size() + 7));
      x.push_back(f * x0.back());
      v.push_back(dem::Vec3::Zero());
    }
  const upscale::StrainReference ref = upscale::make_strain_reference(id, x0, grid, 0.0, 0);
  return upscale::grid_strain(ref, grid, {id, x, v}, {0.5, 500}, {});
}

}  // namespace

TEST(StrainFields, AffineMotionGivesItsMeasuresAndInvalidCellsAreZero) {
  dem::Mat3 f;
  f << 1.2, 0.4, 0.0, 0.0, 0.9, 0.1, 0.0, 0.0, 0.8;
  const upscale::GridStrain strain = sheared_packing(f);
  const upscale::GridFields g = upscale::grid_fields_from_strain(strain);
  EXPECT_EQ(g.num_cells(), 12);
  EXPECT_EQ(g.step, 500);
  const upscale::StrainMeasures exact = upscale::strain_measures(f);
  ASSERT_TRUE(exact.valid);
  for (const char* d : {"best_fit", "tessellation"}) {
    const std::string b = d;
    for (int c = 0; c < 12; ++c) {
      if (c == 4) {
        EXPECT_EQ(g[b + "_F_valid"][c], 0.0);
        EXPECT_EQ(g[b + "_F_reason"][c], static_cast<double>(upscale::StrainReason::too_few_particles));
        EXPECT_EQ(g[b + "_ln_J"][c], 0.0);
        EXPECT_EQ(g[b + "_hencky_xx"][c], 0.0);
        continue;
      }
      EXPECT_EQ(g[b + "_F_valid"][c], 1.0) << d << " cell " << c;
      EXPECT_NEAR(g[b + "_ln_J"][c], std::log(f.determinant()), 1e-12) << d << " cell " << c;
      EXPECT_NEAR(g[b + "_equivalent_shear_strain"][c], exact.equivalent_shear_strain, 1e-12);
      EXPECT_NEAR(g[b + "_F_xy"][c], 0.4, 1e-12);
      EXPECT_NEAR(g[b + "_hencky_zy"][c], exact.hencky_left(2, 1), 1e-12);
    }
  }
  EXPECT_EQ(g["particles"][4], 2.0);
}

TEST(StrainFields, WrittenThroughTheMeshAsCellDataReadBackExactly) {
  dem::Mat3 f;
  f << 1.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0;  // simple shear, gamma = 1
  const upscale::GridFields g = upscale::grid_fields_from_strain(sheared_packing(f));
  int pid = static_cast<int>(::getpid()), rank = 0;
  MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const fs::path dir = fs::temp_directory_path() / ("upgrain_strain_fields_" + std::to_string(pid));
  upscale::UpscaleOptions options;
  options.project_q1 = false;
  const upscale::UpscaleResult r = upscale::upscale_to_mesh(g, MPI_COMM_WORLD, dir, "strain", options);
  ASSERT_EQ(r.cell_values_read_back.size(), g.names.size());
  for (std::size_t k = 0; k < g.names.size(); ++k)
    for (int c = 0; c < g.num_cells(); ++c)
      EXPECT_EQ(r.cell_values_read_back[k][c], g.values[k][c]) << g.names[k] << " cell " << c;
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    ASSERT_TRUE(fs::exists(dir / "strain.pvtu"));
    std::stringstream pvtu;
    pvtu << std::ifstream(dir / "strain.pvtu").rdbuf();
    for (const char* name : {"best_fit_ln_J", "tessellation_equivalent_shear_strain", "best_fit_F_valid"})
      EXPECT_NE(pvtu.str().find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
    fs::remove_all(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

TEST(StrainFields, ReadFromTheWrittenFileBitForBit) {
  dem::Mat3 f;
  f << 0.9, 0.3, 0.1, -0.2, 1.1, 0.0, 0.05, 0.0, 1.3;
  const upscale::GridStrain strain = sheared_packing(f);
  const upscale::GridFields memory = upscale::grid_fields_from_strain(strain);
  int pid = static_cast<int>(::getpid()), rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const fs::path file = fs::temp_directory_path() /
                        ("upgrain_strain_file_" + std::to_string(pid) + "_" + std::to_string(rank) + ".h5");
  upscale::write_grid_strain(file, strain);
  const upscale::GridFields read = upscale::read_strain_fields(file);
  EXPECT_EQ(read.names, memory.names);
  EXPECT_EQ(read.values, memory.values);  // exact
  EXPECT_EQ(read.n, memory.n);
  EXPECT_EQ(read.lo, memory.lo);
  EXPECT_EQ(read.hi, memory.hi);
  EXPECT_EQ(read.time, 0.5);
  EXPECT_EQ(read.step, 500);
  fs::remove(file);
  try {
    (void)upscale::read_strain_fields(file);
    ADD_FAILURE() << "a missing file was read";
  } catch (const upgrain::Error& e) {
    EXPECT_NE(std::string(e.what()).find("grid-strain file " + file.string() + ": no such file"),
              std::string::npos)
        << e.what();
  }
}
