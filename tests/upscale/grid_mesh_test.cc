// Grid fields on the deal.II mesh: the cell data read back bit-identical (on 1 and 2
// ranks: the mpiexec registration runs these same assertions), the Q1 projection keeps
// constants and integrals and converges to the cell values under refinement, and the VTU
// pieces and PVTU record appear complete with nothing else left in the folder.
#include <gtest/gtest.h>
#include <mpi.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include "dem/core/error.h"
#include "upscale/grid_mesh.h"

using namespace upgrain;
namespace fs = std::filesystem;

namespace {

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
int ranks() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// One folder shared by all ranks (named after rank 0's process), removed at the end.
struct SharedScratch {
  fs::path dir;
  SharedScratch() {
    int pid = static_cast<int>(::getpid());
    MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
    dir = fs::temp_directory_path() / ("upgrain_upscale_mesh_" + std::to_string(pid));
  }
  ~SharedScratch() {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank() == 0) fs::remove_all(dir);
  }
};

upscale::GridFields make_grid(std::array<int, 3> n) {
  upscale::GridFields g;
  g.n = n;
  g.lo = {-0.25, 0.0, 0.1};
  g.hi = {0.5, 0.4, 1.3};
  return g;
}

// value = 1000 i + 100 j + 10 k + 0.5: each cell's own value, any misplacement shows.
std::vector<double> index_field(const upscale::GridFields& g) {
  std::vector<double> v(g.num_cells());
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        v[(k * g.n[1] + j) * g.n[0] + i] = 1000.0 * i + 100.0 * j + 10.0 * k + 0.5;
  return v;
}

// Same numbers on every rank: a fixed seed and the same binary.
std::vector<double> random_field(const upscale::GridFields& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1e5, 1e5);
  std::vector<double> v(g.num_cells());
  for (double& x : v) x = u(rng);
  return v;
}

// Linear in z, sampled at the cell centres.
std::vector<double> linear_z_field(const upscale::GridFields& g, double a, double b) {
  std::vector<double> v(g.num_cells());
  const double h = (g.hi[2] - g.lo[2]) / g.n[2];
  for (int c = 0; c < g.num_cells(); ++c) v[c] = a + b * (g.lo[2] + h * (c / (g.n[0] * g.n[1]) + 0.5));
  return v;
}

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct RoundTripCase {
  std::array<int, 3> n;
  unsigned refinements;
};
void PrintTo(const RoundTripCase& c, std::ostream* os) {
  *os << c.n[0] << "x" << c.n[1] << "x" << c.n[2] << ", " << c.refinements << " refinements";
}

class RoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

}  // namespace

TEST_P(RoundTrip, CellDataReadBackIsExact) {
  const auto [n, refinements] = GetParam();
  auto g = make_grid(n);
  g.add("index", index_field(g));
  g.add("random", random_field(g, 2024));
  g.add("negative_tiny", random_field(g, 5));
  for (double& x : g.values[2]) x *= -1e-300;
  const SharedScratch scratch;
  const auto r = upscale::upscale_to_mesh(g, MPI_COMM_WORLD, scratch.dir, "round_trip", {refinements, true});
  ASSERT_EQ(r.cell_values_read_back.size(), g.values.size());
  for (std::size_t k = 0; k < g.values.size(); ++k)
    EXPECT_EQ(r.cell_values_read_back[k], g.values[k]) << g.names[k];
}

INSTANTIATE_TEST_SUITE_P(Grids, RoundTrip,
                         ::testing::Values(RoundTripCase{{3, 3, 4}, 0}, RoundTripCase{{3, 3, 4}, 1},
                                           RoundTripCase{{5, 4, 3}, 0}, RoundTripCase{{5, 4, 3}, 1}),
                         [](const auto& test_info) {
                           const auto& p = test_info.param;
                           return std::to_string(p.n[0]) + "x" + std::to_string(p.n[1]) + "x" +
                                  std::to_string(p.n[2]) + "_refined" + std::to_string(p.refinements);
                         });

TEST(Projection, ConstantStaysConstantAndIntegralsAgree) {
  auto g = make_grid({5, 4, 3});
  g.add("constant", std::vector<double>(g.num_cells(), -2.5e4));
  g.add("random", random_field(g, 11));
  const SharedScratch scratch;
  const double volume = (g.hi[0] - g.lo[0]) * (g.hi[1] - g.lo[1]) * (g.hi[2] - g.lo[2]);
  for (unsigned refinements : {0u, 1u}) {
    const auto r =
        upscale::upscale_to_mesh(g, MPI_COMM_WORLD, scratch.dir, "projection", {refinements, true});
    EXPECT_LE(max_abs_difference(r.q1_cell_means[0], g.values[0]), 1e-12 * 2.5e4);
    EXPECT_NEAR(r.q1_integral[0], -2.5e4 * volume, 1e-12 * 2.5e4 * volume);
    EXPECT_NEAR(r.cellwise_integral[0], -2.5e4 * volume, 1e-12 * 2.5e4 * volume);
    // int u_h = 1^T M u = 1^T b = int f_h (the shape functions sum to one): the projection
    // keeps the integral up to the CG residual.
    const double scale = std::abs(r.cellwise_integral[1]);
    EXPECT_NEAR(r.q1_integral[1], r.cellwise_integral[1], 1e-12 * scale);
    if (rank() == 0)
      std::printf(
          "[ measured ] refinements %u: constant max mean error %.3g, random integral rel. error %.3g, "
          "max CG iterations %u\n",
          refinements, max_abs_difference(r.q1_cell_means[0], g.values[0]) / 2.5e4,
          std::abs(r.q1_integral[1] - r.cellwise_integral[1]) / scale, r.max_cg_iterations);
  }
}

// f = 3 + 2 z sampled at cell centres is a staircase with equal steps s. The field depends
// on z only and the mesh is a tensor product, so u_h is the 1-D projection in z (M and b
// factor). For one step of height s between nodes of spacing h, the 1-D projection is
// u_i = f_i -/+ (s/2) lambda^|i| with lambda = sqrt(3) - 2 (from the stencil h/6 (1, 4, 1)),
// which moves an integral of s h sqrt(3)/12 across the step. An interior grid cell has a step
// of the same height on both sides and these cancel (up to lambda^(2^r)); the end cells have
// one step each, so their mean is off by s sqrt(3)/12 h/H = s sqrt(3)/12 2^-r, r refinements.
TEST(Projection, LinearFieldCellMeansConvergeUnderRefinement) {
  auto g = make_grid({1, 1, 6});
  g.add("linear_z", linear_z_field(g, 3.0, 2.0));
  const double step = 2.0 * (g.hi[2] - g.lo[2]) / g.n[2];
  const SharedScratch scratch;
  double previous = 1.0;
  for (unsigned refinements : {0u, 1u, 2u, 3u}) {
    const auto r = upscale::upscale_to_mesh(g, MPI_COMM_WORLD, scratch.dir, "linear", {refinements, true});
    std::vector<double> error(6);  // (mean of u_h - f) / s per grid cell, bottom to top
    for (int k = 0; k < 6; ++k) error[k] = (r.q1_cell_means[0][k] - g.values[0][k]) / step;
    const double worst = max_abs_difference(r.q1_cell_means[0], g.values[0]) / step;
    EXPECT_LT(worst, previous);  // 0.106, 0.077, 0.036, 0.018: the rate is checked below
    previous = worst;
    EXPECT_NEAR(r.q1_integral[0], r.cellwise_integral[0], 1e-12 * std::abs(r.cellwise_integral[0]));
    if (refinements >= 2) {  // the two end cells' steps are then 2^r mesh cells apart
      const double predicted = std::sqrt(3.0) / 12.0 / (1 << refinements);
      EXPECT_NEAR(error[0], predicted, 0.01 * predicted);
      EXPECT_NEAR(error[5], -predicted, 0.01 * predicted);
      for (int k = 1; k < 5; ++k) EXPECT_LT(std::abs(error[k]), 0.01 * predicted) << "cell " << k;
    }
    if (rank() == 0) {
      std::printf("[ measured ] refinements %u: (mean(u_h) - f) / s by cell:", refinements);
      for (double e : error) std::printf(" %.4g", e);
      std::printf("\n");
    }
  }
}

TEST(Output, PvtuNamesCompletePiecesAndNothingElseIsLeft) {
  auto g = make_grid({3, 3, 4});
  g.add("bagi_s_zz", index_field(g));
  g.add("particles", random_field(g, 3));
  g.time = 0.5;
  g.step = 1234;
  const SharedScratch scratch;
  const fs::path folder = scratch.dir / "vtu";  // created by upscale_to_mesh
  const auto r = upscale::upscale_to_mesh(g, MPI_COMM_WORLD, folder, "bed", {1, true});
  ASSERT_EQ(r.written_files.size(), 1u + ranks());
  EXPECT_EQ(r.written_files[0], (folder / "bed.pvtu").string());
  MPI_Barrier(MPI_COMM_WORLD);
  std::set<std::string> expected{"bed.pvtu"}, present;
  for (const auto& e : fs::directory_iterator(folder)) present.insert(e.path().filename().string());
  const std::string pvtu = read_text(folder / "bed.pvtu");
  int total_cells = 0;
  for (int p = 0; p < ranks(); ++p) {
    const std::string piece = "bed." + std::to_string(p) + ".vtu";
    expected.insert(piece);
    EXPECT_NE(pvtu.find("Source=\"" + piece + "\""), std::string::npos) << pvtu;
    const std::string vtu = read_text(folder / piece);
    EXPECT_NE(vtu.find("</VTKFile>"), std::string::npos) << piece << " is incomplete";
    std::smatch m;
    ASSERT_TRUE(std::regex_search(vtu, m, std::regex("NumberOfCells=\"([0-9]+)\""))) << piece;
    const int cells = std::stoi(m[1]);
    EXPECT_GT(cells, 0) << piece;  // on 2 ranks the mesh is split, each piece has cells
    total_cells += cells;
  }
  EXPECT_EQ(total_cells, 36 * 8);
  EXPECT_EQ(present, expected);  // no staging folder, no temporary file
  for (const char* name : {"\"bagi_s_zz\"", "\"bagi_s_zz_q1\"", "\"particles_q1\"", "\"subdomain\""})
    EXPECT_NE(pvtu.find(name), std::string::npos) << name;

  // Written again: the files are replaced, still nothing else in the folder.
  const auto again = upscale::upscale_to_mesh(g, MPI_COMM_WORLD, folder, "bed", {0, false});
  EXPECT_TRUE(again.q1_cell_means.empty());
  EXPECT_EQ(again.cell_values_read_back, g.values);
  MPI_Barrier(MPI_COMM_WORLD);
  present.clear();
  for (const auto& e : fs::directory_iterator(folder)) present.insert(e.path().filename().string());
  EXPECT_EQ(present, expected);
  EXPECT_EQ(read_text(folder / "bed.pvtu").find("_q1"), std::string::npos);
}

TEST(Output, ErrorsLeaveNothingBehind) {
  auto g = make_grid({2, 2, 2});
  g.add("ok", std::vector<double>(8, 1.0));
  const SharedScratch scratch;
  // A file where the output folder should be: refused on every rank, nothing written.
  if (rank() == 0) {
    fs::create_directories(scratch.dir);
    std::ofstream(scratch.dir / "blocked") << "x";
  }
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_THROW((void)upscale::upscale_to_mesh(g, MPI_COMM_WORLD, scratch.dir / "blocked", "x"), Error);
  MPI_Barrier(MPI_COMM_WORLD);
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(scratch.dir)) ++entries;
  EXPECT_EQ(entries, 1u);

  auto bad = g;
  bad.names[0] = "not a vtu name";
  try {
    (void)upscale::upscale_to_mesh(bad, MPI_COMM_WORLD, scratch.dir, "x");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a vtu name"), std::string::npos) << e.what();
  }
}

TEST(Projection, NonFiniteFieldIsWrittenButNotProjected) {
  auto g = make_grid({2, 2, 2});
  std::vector<double> rai(8, 0.1);
  rai[3] = std::numeric_limits<double>::infinity();  // an RAI with no symmetric shear part
  g.add("rai", rai);
  g.add("ok", std::vector<double>(8, 1.0));
  const SharedScratch scratch;
  const auto r = upscale::upscale_to_mesh(g, MPI_COMM_WORLD, scratch.dir, "inf", {0, true});
  EXPECT_EQ(r.cell_values_read_back[0], rai);
  EXPECT_TRUE(std::isnan(r.q1_integral[0]));
  EXPECT_NEAR(r.q1_integral[1], r.cellwise_integral[1], 1e-12 * r.cellwise_integral[1]);
}
