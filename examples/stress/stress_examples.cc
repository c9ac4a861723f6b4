// Yan and Regueiro's stress tables (docs/stress.md) on beds of monodisperse spheres (r = 1.5 mm) relaxed to
// static equilibrium (docs/stress.md):
//   stress_examples symmetry OUT N...        Tables 2 and 4: symmetry against particle
//                                            count, every formula on each bed;
//   stress_examples ellipsoids OUT N...      Table 3: the same on their polydisperse
//                                            ellipsoid beds (four shapes, a = 1.0-2.5 mm);
//   stress_examples grids OUT N nx,ny,nz...  Tables 6 and 7: per-grid stress on one bed
//                                            for several grid sizes.
// Writes CSV tables into OUT and prints them; paper_tables.py runs both and plots.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "dem/io/grid_stress_output.h"
#include "dem/parallel/mpi_start.h"
#include "dem/stress/asymmetry.h"
#include "tests/common/relaxed_bed.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int symmetry(const std::filesystem::path& out, const std::vector<long>& counts, bool ellipsoids) {
  std::ofstream table(out / (ellipsoids ? "symmetry_ellipsoids.csv" : "symmetry.csv"));
  table.precision(17);
  table << "count,box_side_m,deposition_steps_s,fire_steps,force_residual,torque_residual,settled_bagi_rai,"
           "formula,"
           "rai,s_xx,s_yy,s_zz,s_xy,s_yx\n";
  std::printf("%7s %8s %10s %12s %12s %12s %12s %12s %10s %10s\n", "count", "FIRE", "residual",
              "settled bagi", "bagi RAI%", "weber RAI%", "drescher", "mod. nicot", "bagi szz", "weber szz");
  for (long n : counts) {
    const auto t0 = std::chrono::steady_clock::now();
    const SceneConfig s = ellipsoids ? test::paper_ellipsoid_bed_scene(n) : test::paper_bed_scene(n);
    test::RelaxedBed bed = test::relaxed_bed(s, 1e-4, false);
    const int one[3] = {1, 1, 1};
    const double deposit_seconds = seconds_since(t0);
    // Bagi's asymmetry of the bed as settled (kinetic/released energy 1e-4), then relaxed.
    const double settled_rai =
        relative_asymmetry_index(test::bed_stress(*bed.sim, one)[StressFormula::bagi][0]);
    RelaxationOptions relax;
    if (ellipsoids) relax.max_steps = 1000000;  // 129,249 FIRE steps for 69 grains
    bed.relaxation = relax_to_equilibrium(*bed.sim, relax);
    const GridStress g = test::bed_stress(*bed.sim, one);
    const RelaxationResult res = equilibrium_residual(*bed.sim);
    for (int k = 0; k < kStressFormulaCount; ++k) {
      const auto f = static_cast<StressFormula>(k);
      const Mat3& m = g[f][0];
      table << n << "," << s.container.lx << "," << deposit_seconds << "," << bed.relaxation.steps << ","
            << res.max_force_residual << "," << res.max_torque_residual << "," << settled_rai << ","
            << io::field_name(f) << "," << relative_asymmetry_index(m) << "," << m(0, 0) << "," << m(1, 1)
            << "," << m(2, 2) << "," << m(0, 1) << "," << m(1, 0) << "\n";
    }
    auto rai = [&](StressFormula f) { return 100.0 * relative_asymmetry_index(g[f][0]); };
    std::printf("%7ld %8ld %10.2e %12.3g %12.3g %12.3g %12.3g %12.3g %10.4g %10.4g   (%.0f s)\n", n,
                bed.relaxation.steps, std::max(res.max_force_residual, res.max_torque_residual),
                100 * settled_rai, rai(StressFormula::bagi), rai(StressFormula::weber),
                rai(StressFormula::drescher), rai(StressFormula::modified_nicot),
                g[StressFormula::bagi][0](2, 2), g[StressFormula::weber][0](2, 2), seconds_since(t0));
    if (n == counts.back()) {
      // Table 4: the full tensors of every formula on the largest bed.
      std::ofstream t4(out / (ellipsoids ? "formulas_ellipsoids.csv" : "formulas.csv"));
      t4.precision(17);
      t4 << "count,formula,rai,s_xx,s_xy,s_xz,s_yx,s_yy,s_yz,s_zx,s_zy,s_zz\n";
      std::printf("\nEvery formula on the %ld-%s bed (Pa; RAI in %%):\n", n,
                  ellipsoids ? "ellipsoid" : "sphere");
      for (int k = 0; k < kStressFormulaCount; ++k) {
        const auto f = static_cast<StressFormula>(k);
        const Mat3& m = g[f][0];
        t4 << n << "," << io::field_name(f) << "," << relative_asymmetry_index(m);
        for (int e = 0; e < 9; ++e) t4 << "," << m(e / 3, e % 3);
        t4 << "\n";
        std::printf("  %-18s RAI %10.3g  [%9.4g %9.4g %9.4g; %9.4g %9.4g %9.4g; %9.4g %9.4g %9.4g]\n",
                    std::string(name_of(f)).c_str(), 100 * relative_asymmetry_index(m), m(0, 0), m(0, 1),
                    m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2));
      }
    }
    std::fflush(stdout);
  }
  return 0;
}

int grids(const std::filesystem::path& out, long n, const std::vector<std::array<int, 3>>& specs) {
  const auto t0 = std::chrono::steady_clock::now();
  SceneConfig s = test::paper_bed_scene(n);
  // Their 7,200-sphere bed stands in a box about 1.5 times as high as wide.
  const double grain = 4.0 / 3.0 * std::numbers::pi * std::pow(1.5e-3, 3);
  s.container.lx = s.container.ly = std::cbrt(n * grain / 0.6 / 1.5);
  test::RelaxedBed bed = test::relaxed_bed(s);
  const RelaxationResult res = equilibrium_residual(*bed.sim);
  std::printf(
      "%ld spheres in a %.4f m square box: deposited and relaxed in %.0f s (FIRE %ld steps, residual %.2e)\n",
      n, s.container.lx, seconds_since(t0), bed.relaxation.steps,
      std::max(res.max_force_residual, res.max_torque_residual));
  for (const auto& c : specs) {
    RegularGrid grid;
    const GridStress g = test::bed_stress(*bed.sim, c.data(), &grid);
    char name[64];
    std::snprintf(name, sizeof name, "grid_%dx%dx%d.csv", c[0], c[1], c[2]);
    std::ofstream t(out / name);
    t.precision(17);
    t << "cell,i,j,k,x,y,z,particles,solid_fraction,bagi_s_zz,bagi_s_xx,bagi_s_yy,bagi_rai,weber_rai,"
         "modified_nicot_s_zz\n";
    double max_rai = 0.0;
    for (int cell = 0; cell < grid.num_cells(); ++cell) {
      const int i = cell % c[0], j = (cell / c[0]) % c[1], k = cell / (c[0] * c[1]);
      const Vec3 x = grid.cell_centre(cell);
      const Mat3& b = g[StressFormula::bagi][cell];
      const double rai = relative_asymmetry_index(b);
      if (g.particles[cell] > 0) max_rai = std::max(max_rai, rai);
      t << cell << "," << i << "," << j << "," << k << "," << x.x() << "," << x.y() << "," << x.z() << ","
        << g.particles[cell] << "," << g.solid_fraction[cell] << "," << b(2, 2) << "," << b(0, 0) << ","
        << b(1, 1) << "," << rai << "," << relative_asymmetry_index(g[StressFormula::weber][cell]) << ","
        << g[StressFormula::modified_nicot][cell](2, 2) << "\n";
    }
    std::printf(
        "\n%d x %d x %d grids (top at %.4f m): Bagi sigma_zz (Pa) of the centre and a corner column, top "
        "to bottom; largest Bagi RAI %.3g %%\n",
        c[0], c[1], c[2], grid.hi.z(), 100 * max_rai);
    std::printf("  %8s %12s %12s %10s\n", "z (m)", "centre", "corner", "grains");
    for (int k = c[2] - 1; k >= 0; --k) {
      const int centre = (k * c[1] + c[1] / 2) * c[0] + c[0] / 2, corner = k * c[1] * c[0];
      std::printf("  %8.4f %12.5g %12.5g %10ld\n", grid.cell_centre(centre).z(),
                  g[StressFormula::bagi][centre](2, 2), g[StressFormula::bagi][corner](2, 2),
                  g.particles[centre]);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  upgrain::dem::MpiSession mpi(argc, argv);  // the engine runs on MPI_COMM_SELF
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: stress_examples symmetry OUT N...\n"
                 "       stress_examples ellipsoids OUT N...\n"
                 "       stress_examples grids OUT N nx,ny,nz...\n");
    return 2;
  }
  const std::string mode = argv[1];
  const std::filesystem::path out = argv[2];
  std::filesystem::create_directories(out);
  if (mode == "symmetry") {
    std::vector<long> counts;
    for (int k = 3; k < argc; ++k) counts.push_back(std::stol(argv[k]));
    return symmetry(out, counts, false);
  }
  if (mode == "ellipsoids") {
    std::vector<long> counts;
    for (int k = 3; k < argc; ++k) counts.push_back(std::stol(argv[k]));
    return symmetry(out, counts, true);
  }
  if (mode == "grids" && argc >= 5) {
    std::vector<std::array<int, 3>> specs;
    for (int k = 4; k < argc; ++k) {
      std::array<int, 3> c{};
      if (std::sscanf(argv[k], "%d,%d,%d", &c[0], &c[1], &c[2]) != 3 || c[0] < 1 || c[1] < 1 || c[2] < 1) {
        std::fprintf(stderr, "stress_examples: '%s' is not a grid nx,ny,nz\n", argv[k]);
        return 2;
      }
      specs.push_back(c);
    }
    return grids(out, std::stol(argv[3]), specs);
  }
  std::fprintf(stderr, "stress_examples: unknown mode '%s'\n", mode.c_str());
  return 2;
}
