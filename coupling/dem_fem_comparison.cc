#include "coupling/dem_fem_comparison.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dem/io/atomic_file.h"
#include "dem/io/grid_stress_output.h"

namespace upgrain::coupling {

namespace {

constexpr const char* kComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};

double component(const dem::Mat3& m, int e) { return m(e / 3, e % 3); }

int cell_index(const dem::RegularGrid& g, int i, int j, int k) { return (k * g.n[1] + j) * g.n[0] + i; }

// (max - min) / |mean| over a level of cells with grains; 0 when the level is empty.
template <class Value>
double spread(const dem::RegularGrid& g, const dem::GridStress& dem, int k, Value value) {
  double lo = INFINITY, hi = -INFINITY, sum = 0.0;
  int count = 0;
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) {
      const int c = cell_index(g, i, j, k);
      if (dem.particles[c] == 0) continue;
      const double v = value(c);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      sum += v;
      ++count;
    }
  return count > 0 && sum != 0.0 ? (hi - lo) / std::abs(sum / count) : 0.0;
}

}  // namespace

DemFemComparison compare_dem_fem(const dem::RegularGrid& grid, const dem::GridStress& dem,
                                 const std::vector<Tensor9>& fem, const fem::ConfinedColumn& column,
                                 const std::vector<dem::StressFormula>& formulas) {
  DemFemComparison c;
  c.grid = grid;
  c.fem = fem;
  c.k0 = column.k0();
  c.centre_i = grid.n[0] / 2;
  c.centre_j = grid.n[1] / 2;
  c.edge_i = 0;
  c.edge_j = grid.n[1] / 2;
  const int cells = grid.num_cells();
  c.analytic_szz.resize(cells);
  for (int cell = 0; cell < cells; ++cell)
    c.analytic_szz[cell] = column.vertical_stress(grid.cell_centre(cell).z());
  for (int k = 0; k < grid.n[2]; ++k)
    c.fem_level_spread.push_back(spread(grid, dem, k, [&](int cell) { return fem[cell][8]; }));
  {
    int filled = 0;
    for (int cell = 0; cell < cells; ++cell) {
      if (dem.particles[cell] == 0 || fem[cell][8] == 0.0) continue;
      c.fem_mean_lateral_ratio += 0.5 * (fem[cell][0] + fem[cell][4]) / fem[cell][8];
      ++filled;
    }
    if (filled) c.fem_mean_lateral_ratio /= filled;
  }

  for (dem::StressFormula f : formulas) {
    FormulaComparison fc;
    fc.formula = f;
    Tensor9 diff2{};
    double fem_zz2 = 0.0, ratio = 0.0;
    int filled = 0;
    for (int cell = 0; cell < cells; ++cell) {
      if (dem.particles[cell] == 0) continue;
      const dem::Mat3& s = dem[f][cell];
      for (int e = 0; e < 9; ++e) diff2[e] += std::pow(component(s, e) - fem[cell][e], 2);
      fem_zz2 += fem[cell][8] * fem[cell][8];
      if (s(2, 2) != 0.0) ratio += 0.5 * (s(0, 0) + s(1, 1)) / s(2, 2);
      ++filled;
    }
    for (int e = 0; e < 9; ++e) fc.relative_l2[e] = fem_zz2 > 0.0 ? std::sqrt(diff2[e] / fem_zz2) : 0.0;
    fc.mean_lateral_ratio = filled ? ratio / filled : 0.0;
    for (int k = 0; k < grid.n[2]; ++k)
      fc.level_spread.push_back(spread(grid, dem, k, [&](int cell) { return dem[f][cell](2, 2); }));
    c.formulas.push_back(fc);
  }
  return c;
}

void write_comparison_tables(const std::filesystem::path& folder, const DemFemComparison& c,
                             const dem::GridStress& dem) {
  const dem::RegularGrid& g = c.grid;
  {
    std::ostringstream t;
    t.precision(17);
    t << "# DEM grid stress beside the continuum (FEM cell averages) and the analytic column; Pa, "
         "compression negative, sigma_ij = (1/V) sum f_i l_j\n"
         "cell,i,j,k,x,y,z,particles,formula";
    for (const char* comp : kComponents) t << ",dem_s_" << comp;
    for (const char* comp : kComponents) t << ",fem_s_" << comp;
    for (const char* comp : kComponents) t << ",diff_s_" << comp;
    t << ",analytic_s_zz\n";
    for (int cell = 0; cell < g.num_cells(); ++cell) {
      const int i = cell % g.n[0], j = (cell / g.n[0]) % g.n[1], k = cell / (g.n[0] * g.n[1]);
      const dem::Vec3 x = g.cell_centre(cell);
      for (const FormulaComparison& fc : c.formulas) {
        const dem::Mat3& s = dem[fc.formula][cell];
        t << cell << "," << i << "," << j << "," << k << "," << x.x() << "," << x.y() << "," << x.z() << ","
          << dem.particles[cell] << "," << dem::io::field_name(fc.formula);
        for (int e = 0; e < 9; ++e) t << "," << component(s, e);
        for (int e = 0; e < 9; ++e) t << "," << c.fem[cell][e];
        for (int e = 0; e < 9; ++e) t << "," << component(s, e) - c.fem[cell][e];
        t << "," << c.analytic_szz[cell] << "\n";
      }
    }
    dem::io::write_text_atomically(folder / "comparison_cells.csv", t.str());
  }
  {
    std::ostringstream t;
    t.precision(17);
    t << "# sigma_zz (Pa) and lateral ratio (s_xx + s_yy) / (2 s_zz) against height for the centre and an "
         "edge "
         "column of grid cells; K0 = nu / (1 - nu) of the continuum\n"
         "column,i,j,k,z,particles,k0,fem_s_zz,fem_ratio,analytic_s_zz";
    for (const FormulaComparison& fc : c.formulas) {
      const std::string n = dem::io::field_name(fc.formula);
      t << "," << n << "_s_zz," << n << "_ratio";
    }
    t << "\n";
    const struct {
      const char* name;
      int i, j;
    } columns[] = {{"centre", c.centre_i, c.centre_j}, {"edge", c.edge_i, c.edge_j}};
    for (const auto& col : columns) {
      for (int k = 0; k < g.n[2]; ++k) {
        const int cell = cell_index(g, col.i, col.j, k);
        const Tensor9& f = c.fem[cell];
        t << col.name << "," << col.i << "," << col.j << "," << k << "," << g.cell_centre(cell).z() << ","
          << dem.particles[cell] << "," << c.k0 << "," << f[8] << "," << 0.5 * (f[0] + f[4]) / f[8] << ","
          << c.analytic_szz[cell];
        for (const FormulaComparison& fc : c.formulas) {
          const dem::Mat3& s = dem[fc.formula][cell];
          t << "," << s(2, 2) << "," << (s(2, 2) != 0.0 ? 0.5 * (s(0, 0) + s(1, 1)) / s(2, 2) : 0.0);
        }
        t << "\n";
      }
    }
    dem::io::write_text_atomically(folder / "profiles.csv", t.str());
  }
  {
    std::ostringstream t;
    t.precision(17);
    t << "# ||sigma_dem,ij - sigma_fem,ij|| / ||sigma_fem,zz|| over the cells with grains; mean lateral "
         "ratio; "
         "spread of s_zz across each level ((max - min) / |mean|)\nformula";
    for (const char* comp : kComponents) t << ",l2_" << comp;
    t << ",mean_lateral_ratio";
    for (int k = 0; k < g.n[2]; ++k) t << ",level_spread_" << k;
    t << "\n";
    for (const FormulaComparison& fc : c.formulas) {
      t << dem::io::field_name(fc.formula);
      for (double v : fc.relative_l2) t << "," << v;
      t << "," << fc.mean_lateral_ratio;
      for (double v : fc.level_spread) t << "," << v;
      t << "\n";
    }
    t << "fem";
    for (int e = 0; e < 9; ++e) t << "," << 0.0;
    t << "," << c.fem_mean_lateral_ratio;
    for (double v : c.fem_level_spread) t << "," << v;
    t << "\n";
    dem::io::write_text_atomically(folder / "relative_l2.csv", t.str());
  }
}

}  // namespace upgrain::coupling
