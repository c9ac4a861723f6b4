#include "coupling/studies/continuum/dem_fem_comparison.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "coupling/studies/continuum/wall_shear_profile.h"
#include "dem/files/atomic_file.h"
#include "dem/files/json_number.h"
#include "dem/io/grid_stress_output.h"

namespace upgrain::coupling {

namespace {

constexpr const char* kComponents[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};

double component(const dem::Mat3& m, int e) { return m(e / 3, e % 3); }

int cell_index(const dem::RegularGrid& g, int i, int j, int k) { return (k * g.n[1] + j) * g.n[0] + i; }

// (s_xx + s_yy) / (2 s_zz); 0 where s_zz is 0.
double lateral_ratio(double xx, double yy, double zz) { return zz != 0.0 ? 0.5 * (xx + yy) / zz : 0.0; }

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

// The lateral ratio averaged over the cells with grains, and the spread of each level.
template <class Entry>
void level_statistics(const dem::RegularGrid& g, const dem::GridStress& dem, Entry entry, double& mean_ratio,
                      std::vector<double>& level_spread) {
  double ratio = 0.0;
  int filled = 0;
  for (int cell = 0; cell < g.num_cells(); ++cell) {
    if (dem.particles[cell] == 0 || entry(cell, 8) == 0.0) continue;
    ratio += lateral_ratio(entry(cell, 0), entry(cell, 4), entry(cell, 8));
    ++filled;
  }
  mean_ratio = filled ? ratio / filled : 0.0;
  level_spread.clear();
  for (int k = 0; k < g.n[2]; ++k)
    level_spread.push_back(spread(g, dem, k, [&](int cell) { return entry(cell, 8); }));
}

}  // namespace

DemFemComparison compare_dem_fem(const dem::RegularGrid& grid, const dem::GridStress& dem,
                                 std::vector<ContinuumResult> continua, const fem::ConfinedColumn& column,
                                 double dem_wall_share, const std::vector<dem::StressFormula>& formulas) {
  DemFemComparison c;
  c.grid = grid;
  c.continua = std::move(continua);
  c.k0 = column.k0();
  c.dem_wall_share = dem_wall_share;
  c.centre_i = grid.n[0] / 2;
  c.centre_j = grid.n[1] / 2;
  c.edge_i = 0;
  c.edge_j = grid.n[1] / 2;
  const int cells = grid.num_cells();
  c.analytic_szz.resize(cells);
  double analytic_zz2 = 0.0;  // the common denominator of every Difference
  for (int cell = 0; cell < cells; ++cell) {
    // Heights from the grid's floor, which is the continuum's floor.
    c.analytic_szz[cell] = column.vertical_stress(grid.cell_centre(cell).z() - grid.lo.z());
    if (dem.particles[cell] != 0) analytic_zz2 += c.analytic_szz[cell] * c.analytic_szz[cell];
  }
  for (ContinuumResult& r : c.continua)
    level_statistics(
        grid, dem, [&](int cell, int e) { return r.cells[cell][e]; }, r.mean_lateral_ratio, r.level_spread);

  for (dem::StressFormula f : formulas) {
    FormulaComparison fc;
    fc.formula = f;
    level_statistics(
        grid, dem, [&](int cell, int e) { return component(dem[f][cell], e); }, fc.mean_lateral_ratio,
        fc.level_spread);
    for (const ContinuumResult& r : c.continua) {
      Difference d;
      for (int cell = 0; cell < cells; ++cell) {
        if (dem.particles[cell] == 0) continue;
        for (int e = 0; e < 9; ++e)
          d.component[e] += std::pow(component(dem[f][cell], e) - r.cells[cell][e], 2);
      }
      double sum = 0.0;
      for (double& v : d.component) {
        sum += v;
        v = analytic_zz2 > 0.0 ? std::sqrt(v / analytic_zz2) : 0.0;
      }
      d.tensor = analytic_zz2 > 0.0 ? std::sqrt(sum / analytic_zz2) : 0.0;
      fc.against.push_back(d);
    }
    for (std::size_t k = 1; k < fc.against.size(); ++k)
      if (fc.against[k].tensor < fc.against[fc.closest].tensor) fc.closest = k;
    c.formulas.push_back(fc);
  }
  return c;
}

void write_comparison_tables(const std::filesystem::path& folder, const DemFemComparison& c,
                             const dem::GridStress& dem) {
  const dem::RegularGrid& g = c.grid;
  const ContinuumResult& rollers = c.continua.front();
  {
    std::ostringstream t;
    t.precision(17);
    t << "# DEM grid stress beside the continua (FEM cell averages; fem = the elastic column on rollers) and "
         "the analytic column; Pa, compression negative, sigma_ij = (1/V) sum f_i l_j\n"
         "cell,i,j,k,x,y,z,particles,formula";
    for (const char* comp : kComponents) t << ",dem_s_" << comp;
    for (const char* comp : kComponents) t << ",fem_s_" << comp;
    for (const char* comp : kComponents) t << ",diff_s_" << comp;
    t << ",analytic_s_zz";
    for (std::size_t m = 1; m < c.continua.size(); ++m)
      for (const char* comp : kComponents) t << "," << c.continua[m].key << "_s_" << comp;
    t << "\n";
    for (int cell = 0; cell < g.num_cells(); ++cell) {
      const int i = cell % g.n[0], j = (cell / g.n[0]) % g.n[1], k = cell / (g.n[0] * g.n[1]);
      const dem::Vec3 x = g.cell_centre(cell);
      for (const FormulaComparison& fc : c.formulas) {
        const dem::Mat3& s = dem[fc.formula][cell];
        t << cell << "," << i << "," << j << "," << k << "," << x.x() << "," << x.y() << "," << x.z() << ","
          << dem.particles[cell] << "," << dem::io::field_name(fc.formula);
        for (int e = 0; e < 9; ++e) t << "," << component(s, e);
        for (int e = 0; e < 9; ++e) t << "," << rollers.cells[cell][e];
        for (int e = 0; e < 9; ++e) t << "," << component(s, e) - rollers.cells[cell][e];
        t << "," << c.analytic_szz[cell];
        for (std::size_t m = 1; m < c.continua.size(); ++m)
          for (int e = 0; e < 9; ++e) t << "," << c.continua[m].cells[cell][e];
        t << "\n";
      }
    }
    dem::io::write_text_atomically(folder / "comparison_cells.csv", t.str());
  }
  {
    std::ostringstream t;
    t.precision(17);
    t << "# sigma_zz (Pa) and lateral ratio (s_xx + s_yy) / (2 s_zz) against height for the centre and an "
         "edge "
         "column of grid cells: the continua (fem = elastic on rollers), the hydrostatic column and each DEM "
         "formula; K0 = nu / (1 - nu) of the continuum\n"
         "column,i,j,k,z,particles,k0,fem_s_zz,fem_ratio,analytic_s_zz";
    for (std::size_t m = 1; m < c.continua.size(); ++m)
      t << "," << c.continua[m].key << "_s_zz," << c.continua[m].key << "_ratio";
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
        const Tensor9& f = rollers.cells[cell];
        t << col.name << "," << col.i << "," << col.j << "," << k << "," << g.cell_centre(cell).z() << ","
          << dem.particles[cell] << "," << c.k0 << "," << f[8] << "," << lateral_ratio(f[0], f[4], f[8])
          << "," << c.analytic_szz[cell];
        for (std::size_t m = 1; m < c.continua.size(); ++m) {
          const Tensor9& s = c.continua[m].cells[cell];
          t << "," << s[8] << "," << lateral_ratio(s[0], s[4], s[8]);
        }
        for (const FormulaComparison& fc : c.formulas) {
          const dem::Mat3& s = dem[fc.formula][cell];
          t << "," << s(2, 2) << "," << lateral_ratio(s(0, 0), s(1, 1), s(2, 2));
        }
        t << "\n";
      }
    }
    dem::io::write_text_atomically(folder / "profiles.csv", t.str());
  }
  {
    std::ostringstream t;
    t.precision(17);
    t << "# ||sigma_dem,ij - sigma_continuum,ij|| / ||sigma_zz of the hydrostatic column|| over the cells "
         "with "
         "grains, per DEM formula and continuum; l2_tensor: the whole tensor\nformula,continuum";
    for (const char* comp : kComponents) t << ",l2_" << comp;
    t << ",l2_tensor\n";
    for (const FormulaComparison& fc : c.formulas)
      for (std::size_t m = 0; m < c.continua.size(); ++m) {
        t << dem::io::field_name(fc.formula) << "," << c.continua[m].key;
        for (double v : fc.against[m].component) t << "," << v;
        t << "," << fc.against[m].tensor << "\n";
      }
    dem::io::write_text_atomically(folder / "relative_l2.csv", t.str());
  }
  {
    std::ostringstream t;
    t.precision(17);
    t << "# per DEM formula and continuum: share of the weight the side walls carry (the DEM's from its wall "
         "forces), mean lateral ratio (s_xx + s_yy) / (2 s_zz) over the cells with grains, spread of s_zz "
         "across each level ((max - min) / |mean|)\nsource,kind,label,wall_share,mean_lateral_ratio";
    for (int k = 0; k < g.n[2]; ++k) t << ",level_spread_" << k;
    t << "\n";
    const auto row = [&](const std::string& source, const char* kind, const std::string& label, double share,
                         double ratio, const std::vector<double>& spreads) {
      t << source << "," << kind << "," << label << "," << share << "," << ratio;
      for (double v : spreads) t << "," << v;
      t << "\n";
    };
    for (const FormulaComparison& fc : c.formulas)
      row(dem::io::field_name(fc.formula), "dem", "DEM " + std::string(dem::name_of(fc.formula)),
          c.dem_wall_share, fc.mean_lateral_ratio, fc.level_spread);
    for (const ContinuumResult& r : c.continua)
      row(r.key, "continuum", r.label, r.wall_share, r.mean_lateral_ratio, r.level_spread);
    dem::io::write_text_atomically(folder / "stress_summary.csv", t.str());
  }
  {
    std::ostringstream t;
    t.precision(17);
    t << "# per level of the grid: the side walls' mean upward shear on the fill (Pa; the upward force of "
         "the "
         "four side walls within the level over the perimeter times the level's height; positive where the "
         "walls carry weight). dem: from the side-wall contacts of the final state, binned by their points' "
         "height (empty when they were not recorded)\nlevel,z_lo,z_hi,dem";
    for (const ContinuumResult& r : c.continua) t << "," << r.key;
    t << "\n";
    const double dz = grid_levels(g).dz;
    for (int k = 0; k < g.n[2]; ++k) {
      const auto at = [k](const std::vector<double>& v) {
        return static_cast<std::size_t>(k) < v.size() ? dem::io::json_number(v[static_cast<std::size_t>(k)])
                                                      : std::string();
      };
      t << k << "," << g.lo.z() + k * dz << "," << g.lo.z() + (k + 1) * dz << "," << at(c.dem_wall_shear);
      for (const ContinuumResult& r : c.continua) t << "," << at(r.wall_shear);
      t << "\n";
    }
    dem::io::write_text_atomically(folder / "wall_shear.csv", t.str());
  }
}

}  // namespace upgrain::coupling
