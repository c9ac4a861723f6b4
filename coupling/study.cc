#include "coupling/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "coupling/dem_fem_comparison.h"
#include "coupling/dem_run.h"
#include "coupling/strain_report.h"
#include "dem/core/error.h"
#include "dem/io/atomic_file.h"
#include "dem/io/grid_stress_output.h"
#include "dem/io/json_number.h"
#include "dem/stress/asymmetry.h"
#include "fem/elastic_column.h"
#include "upscale/grid_fields.h"
#include "upscale/grid_mesh.h"

#ifndef UPGRAIN_SCRIPT_DIR
#define UPGRAIN_SCRIPT_DIR ""
#endif

namespace upgrain::coupling {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// What rank 0's DEM run hands to every rank.
struct DemOutcome {
  dem::RegularGrid grid;
  dem::GridStress stress;
  double total_mass = 0.0;
  dem::Vec3 floor_force = dem::Vec3::Zero();
  double side_wall_vertical = 0.0;  // sum of the grains' vertical force on the side walls (N, < 0 = carried)
};

void broadcast(DemOutcome& d, MPI_Comm comm) {
  int n[3] = {d.grid.n[0], d.grid.n[1], d.grid.n[2]};
  MPI_Bcast(n, 3, MPI_INT, 0, comm);
  for (int k = 0; k < 3; ++k) d.grid.n[k] = n[k];
  MPI_Bcast(d.grid.lo.data(), 3, MPI_DOUBLE, 0, comm);
  MPI_Bcast(d.grid.hi.data(), 3, MPI_DOUBLE, 0, comm);
  const int cells = d.grid.num_cells();
  for (auto& s : d.stress.sigma) {
    s.resize(cells);
    MPI_Bcast(s.data(), 9 * cells, MPI_DOUBLE, 0, comm);  // Mat3 is 9 contiguous doubles
  }
  for (auto* v : {&d.stress.particles, &d.stress.internal_contacts, &d.stress.external_contacts,
                  &d.stress.wall_contacts}) {
    v->resize(cells);
    MPI_Bcast(v->data(), cells, MPI_LONG, 0, comm);
  }
  d.stress.solid_fraction.resize(cells);
  MPI_Bcast(d.stress.solid_fraction.data(), cells, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&d.stress.cell_volume, 1, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&d.total_mass, 1, MPI_DOUBLE, 0, comm);
  MPI_Bcast(d.floor_force.data(), 3, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&d.side_wall_vertical, 1, MPI_DOUBLE, 0, comm);
}

upscale::GridFields comparison_fields(const DemOutcome& d, const DemFemComparison& c,
                                      const std::vector<dem::StressFormula>& formulas) {
  upscale::GridFields f = upscale::grid_fields_from_stress(d.grid, d.stress, formulas);
  const int cells = d.grid.num_cells();
  const char* comp[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
  for (int e : {0, 4, 8, 1, 2, 5}) {
    std::vector<double> v(cells);
    for (int k = 0; k < cells; ++k) v[k] = c.fem[k][e];
    f.add(std::string("fem_s_") + comp[e], v);
    for (dem::StressFormula fm : formulas) {
      std::vector<double> diff(cells);
      for (int k = 0; k < cells; ++k) diff[k] = d.stress[fm][k](e / 3, e % 3) - c.fem[k][e];
      f.add("diff_" + dem::io::field_name(fm) + "_s_" + comp[e], diff);
    }
  }
  f.add("analytic_s_zz", c.analytic_szz);
  return f;
}

std::string fmt(double v, int digits = 4) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

void write_report(const std::filesystem::path& folder, const SceneInput& in, const RunResult& r,
                  const DemOutcome& d, const fem::ColumnProblem& problem, const fem::ColumnSolution& sol,
                  const DemFemComparison& c, const std::vector<std::pair<std::string, double>>& timings,
                  const std::vector<std::string>& plots, const std::vector<std::string>& strain_plots,
                  int ranks) {
  const dem::SceneConfig& s = in.scene;
  const double area = s.container.lx * s.container.ly;
  const double weight = d.total_mass * s.gravity;
  std::ostringstream m;
  m << "# Upgrain study: DEM bed against the continuum column\n\n"
    << "Scene: `" << in.source << "`. Written by `upgrain` on " << ranks << " MPI rank(s). "
    << "How to read it: docs/study.md.\n\n## Parameters\n\n| quantity | value |\n|---|---|\n"
    << "| grains | " << s.particles.count << " spheres, radius "
    << (s.particles.gradation.empty() ? fmt(s.particles.radius) + " m" : std::string("by gradation curve"))
    << ", density " << s.particles.material.density << " kg/m^3, E " << s.particles.material.youngs_modulus
    << " Pa, nu " << s.particles.material.poisson_ratio << " |\n"
    << "| contact | friction " << s.friction << ", damping ratio " << s.damping_ratio << ", wall friction "
    << (s.effects.wall_friction ? "floor " + fmt(s.container.friction[0]) + ", sides " +
                                      fmt(s.container.friction[1]) + " " + fmt(s.container.friction[2]) +
                                      " " + fmt(s.container.friction[3]) + " " + fmt(s.container.friction[4])
                                : std::string("off"))
    << " |\n"
    << "| container | " << s.container.lx << " m x " << s.container.ly << " m |\n"
    << "| time step, end time | " << s.time_step << " s, " << s.end_time << " s |\n"
    << "| stress grid | " << d.grid.n[0] << " x " << d.grid.n[1] << " x " << d.grid.n[2]
    << " cells up to z = " << fmt(d.grid.hi.z())
    << " m (top of the highest grain), V = " << fmt(d.stress.cell_volume) << " m^3 |\n"
    << "| continuum | E " << problem.youngs_modulus << " Pa, nu " << problem.poisson_ratio
    << " (K0 = " << fmt(c.k0) << "), Q" << problem.degree << ", " << problem.refinements << " refinement(s), "
    << sol.n_dofs << " dofs, " << sol.cg_iterations << " CG iterations |\n"
    << "| continuum load | bulk density " << fmt(problem.density) << " kg/m^3 = grain mass "
    << fmt(d.total_mass) << " kg / (footprint x " << fmt(problem.height) << " m) |\n\n";

  m << "## Headline figures\n\n";
  m << "- DEM run: " << r.steps << " steps, " << fmt(r.simulated_time) << " s simulated";
  if (r.relaxation)
    m << "; relaxed by FIRE in " << r.relaxation->steps << " steps to residual force "
      << fmt(r.relaxation->max_force_residual, 3) << " and torque "
      << fmt(r.relaxation->max_torque_residual, 3) << " (of m g, m g r)";
  m << ".\n- Weight over the floor area: " << fmt(weight / area)
    << " Pa. Floor force over area: " << fmt(-d.floor_force.z() / area) << " Pa; the side walls carry "
    << fmt(-d.side_wall_vertical / weight * 100 + 0.0, 3) << " % of the weight by friction.\n";
  m << "- Continuum against its analytic solution: relative L2 error of the stress "
    << fmt(sol.l2_error_stress / fem::analytic_solution(problem).stress_l2_norm(area), 3) << ".\n\n";
  m << "| formula | ||Δσ_zz|| / ||σ_zz,FEM|| | ||Δσ_xx|| | ||Δσ_xz|| | mean (σ_xx+σ_yy)/(2σ_zz) | largest "
       "level spread of σ_zz |\n|---|---|---|---|---|---|\n";
  for (const FormulaComparison& fc : c.formulas) {
    m << "| " << dem::name_of(fc.formula) << " | " << fmt(fc.relative_l2[8], 3) << " | "
      << fmt(fc.relative_l2[0], 3) << " | " << fmt(fc.relative_l2[2], 3) << " | "
      << fmt(fc.mean_lateral_ratio, 3) << " | "
      << fmt(*std::max_element(fc.level_spread.begin(), fc.level_spread.end()), 3) << " |\n";
  }
  m << "| continuum (FEM) | 0 | 0 | 0 | " << fmt(c.fem_mean_lateral_ratio, 3) << " (K0 " << fmt(c.k0, 3)
    << ") | " << fmt(*std::max_element(c.fem_level_spread.begin(), c.fem_level_spread.end()), 3) << " |\n\n"
    << "A continuum with frictionless walls has a uniform σ_zz across each level (spread 0); the DEM bed "
       "does not: walls and the packing carry the load unevenly (the paper's microstructural effect).\n\n";

  m << "## σ_zz against height, centre and edge columns (Pa)\n\n| column | z (m) | FEM | analytic";
  for (const FormulaComparison& fc : c.formulas) m << " | " << dem::name_of(fc.formula);
  m << " |\n|---|---|---|---";
  for (std::size_t k = 0; k < c.formulas.size(); ++k) m << "|---";
  m << "|\n";
  const dem::RegularGrid& g = d.grid;
  for (auto [name, i, j] : {std::tuple<const char*, int, int>{"centre", c.centre_i, c.centre_j},
                            std::tuple<const char*, int, int>{"edge", c.edge_i, c.edge_j}}) {
    for (int k = g.n[2] - 1; k >= 0; --k) {
      const int cell = (k * g.n[1] + j) * g.n[0] + i;
      m << "| " << name << " | " << fmt(g.cell_centre(cell).z()) << " | " << fmt(c.fem[cell][8]) << " | "
        << fmt(c.analytic_szz[cell]);
      for (const FormulaComparison& fc : c.formulas) m << " | " << fmt(d.stress[fc.formula][cell](2, 2));
      m << " |\n";
    }
  }
  m << "\n## Plots\n\n";
  if (plots.empty())
    m << "No plots: /usr/bin/python3 with matplotlib was not available (the CSV tables hold the same "
         "data).\n";
  for (const std::string& p : plots) m << "![" << p << "](" << p << ")\n\n";
  m << "\n## Files\n\n- `comparison_cells.csv`, `profiles.csv`, `relative_l2.csv`: the tables above, in "
       "full.\n"
    << "- `mesh/dem_fem.pvtu`: DEM (per formula), FEM and their difference as cell data on one mesh, with "
       "Q1 projections (ParaView).\n- `fem/column.pvtu`: the continuum solution.\n"
    << "- `grid_stress.xdmf`, `particles.xdmf`: the DEM grid stress and particles over time.\n\n";
  if (r.final_strain) m << strain_section(in, *r.final_strain, folder, strain_plots);
  m << "## Timings (wall clock, rank 0)\n\n| stage | s |\n|---|---|\n";
  for (const auto& [stage, secs] : timings) m << "| " << stage << " | " << fmt(secs, 3) << " |\n";
  dem::io::write_text_atomically(folder / "report.md", m.str());
}

// The headline numbers in machine-readable form (tests/end_to_end/check_study.py).
void write_study_json(const std::filesystem::path& folder, const SceneInput& in, const DemOutcome& d,
                      const fem::ColumnProblem& problem, const fem::ColumnSolution& sol,
                      const DemFemComparison& c, int ranks) {
  const double area = in.scene.container.lx * in.scene.container.ly;
  const fem::ConfinedColumn exact = fem::analytic_solution(problem);
  const auto n = [](double v) { return dem::io::json_number(v); };
  std::ostringstream j;
  j << "{\n  \"ranks\": " << ranks << ",\n  \"grid_cells\": [" << d.grid.n[0] << ", " << d.grid.n[1] << ", "
    << d.grid.n[2] << "],\n  \"grid_top_m\": " << n(d.grid.hi.z())
    << ",\n  \"cell_volume_m3\": " << n(d.stress.cell_volume) << ",\n  \"grain_mass_kg\": " << n(d.total_mass)
    << ",\n  \"weight_N\": " << n(d.total_mass * in.scene.gravity)
    << ",\n  \"floor_force_z_N\": " << n(d.floor_force.z())
    << ",\n  \"side_wall_force_z_N\": " << n(d.side_wall_vertical) << ",\n  \"footprint_m2\": " << n(area)
    << ",\n  \"bulk_density\": " << n(problem.density) << ",\n  \"k0\": " << n(c.k0)
    << ",\n  \"fem_dofs\": " << sol.n_dofs
    << ",\n  \"fem_relative_l2_error_stress\": " << n(sol.l2_error_stress / exact.stress_l2_norm(area))
    << ",\n  \"fem_relative_l2_error_displacement\": "
    << n(sol.l2_error_displacement / exact.displacement_l2_norm(area))
    << ",\n  \"fem_mean_lateral_ratio\": " << n(c.fem_mean_lateral_ratio) << ",\n  \"formulas\": {";
  for (std::size_t k = 0; k < c.formulas.size(); ++k) {
    const FormulaComparison& fc = c.formulas[k];
    j << (k ? "," : "") << "\n    \"" << dem::io::field_name(fc.formula)
      << "\": {\"relative_l2_zz\": " << n(fc.relative_l2[8])
      << ", \"relative_l2_xx\": " << n(fc.relative_l2[0])
      << ", \"mean_lateral_ratio\": " << n(fc.mean_lateral_ratio) << "}";
  }
  j << "\n  }\n}\n";
  dem::io::write_text_atomically(folder / "study.json", j.str());
}

}  // namespace

int run_study(const SceneInput& in, MPI_Comm comm, const std::function<void(const Progress&)>& on_progress,
              const std::function<void(const RunResult&)>& on_dem_done) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const std::filesystem::path folder = in.output.folder;
  std::vector<std::pair<std::string, double>> timings;
  const auto t_all = Clock::now();

  // 1. DEM deposition and grid stress (rank 0).
  RunResult r;
  DemOutcome d;
  auto t0 = Clock::now();
  r = run_dem(in, comm, on_progress);
  on_rank0(comm, [&] {
    if (on_dem_done) on_dem_done(r);
    if (!r.final_stress) throw Error("the DEM run produced no grid stress (Stress/formulas is empty)");
    d.grid = r.final_grid;
    d.stress = *r.final_stress;
    d.total_mass = r.total_mass;
    for (std::size_t w = 0; w < r.wall_forces.size(); ++w) {
      if (r.wall_names[w] == "floor")
        d.floor_force = r.wall_forces[w];
      else
        d.side_wall_vertical += r.wall_forces[w].z();
    }
  });
  timings.emplace_back("DEM deposition, relaxation and grid stress (" + std::to_string(ranks) + " rank" +
                           (ranks > 1 ? "s, " : ", ") + dem::to_string(in.parallel.summation) + " summation)",
                       since(t0));
  broadcast(d, comm);

  // 2. The continuum column of the same container, filled to the grid's top.
  t0 = Clock::now();
  fem::ColumnProblem problem;
  problem.length_x = in.scene.container.lx;
  problem.length_y = in.scene.container.ly;
  problem.height = d.grid.hi.z() - d.grid.lo.z();
  problem.density = d.total_mass / (problem.length_x * problem.length_y * problem.height);
  problem.gravity = in.scene.gravity;
  problem.youngs_modulus = in.study.continuum.youngs_modulus;
  problem.poisson_ratio = in.study.continuum.poisson_ratio;
  problem.cells = {static_cast<unsigned>(d.grid.n[0]), static_cast<unsigned>(d.grid.n[1]),
                   static_cast<unsigned>(d.grid.n[2])};
  problem.refinements = in.study.continuum.refinements;
  problem.degree = in.study.continuum.degree;
  const fem::ColumnSolution sol = fem::solve_column(problem, comm, (folder / "fem").string());
  timings.emplace_back("continuum solve (FEM, output included)", since(t0));

  // 3. Comparison and the one-mesh output.
  t0 = Clock::now();
  std::vector<Tensor9> fem_cells(sol.cell_average_stress.begin(), sol.cell_average_stress.end());
  const DemFemComparison c =
      compare_dem_fem(d.grid, d.stress, fem_cells, fem::analytic_solution(problem), in.study.formulas);
  upscale::UpscaleOptions uo;
  uo.refinements = 0;
  (void)upscale::upscale_to_mesh(comparison_fields(d, c, in.study.formulas), comm, folder / "mesh", "dem_fem",
                                 uo);
  timings.emplace_back("comparison and upscaling to the mesh", since(t0));

  // 4. Tables, plots and the report (rank 0).
  on_rank0(comm, [&] {
    t0 = Clock::now();
    write_comparison_tables(folder, c, d.stress);
    std::vector<std::string> plots;
    const std::string script = std::string(UPGRAIN_SCRIPT_DIR) + "/plot_study.py";
    if (std::filesystem::exists(script) && std::filesystem::exists("/usr/bin/python3")) {
      const std::string cmd = "/usr/bin/python3 '" + script + "' '" + folder.string() + "' > '" +
                              (folder / "plots.log").string() + "' 2>&1";
      if (std::system(cmd.c_str()) == 0)
        for (const char* p : {"profiles_szz.png", "lateral_ratio.png", "level_spread.png"})
          if (std::filesystem::exists(folder / p)) plots.emplace_back(p);
    }
    std::vector<std::string> strain_plots;
    if (r.final_strain) {
      (void)write_strain_mesh(folder);
      strain_plots = plot_strain(folder);
    }
    timings.emplace_back("tables and plots", since(t0));
    timings.emplace_back("whole study", since(t_all));
    write_report(folder, in, r, d, problem, sol, c, timings, plots, strain_plots, ranks);
    write_study_json(folder, in, d, problem, sol, c, ranks);
    std::printf("  study: %d x %d x %d grid, continuum Q%u with %llu dofs (%.2f s), %d rank(s)\n",
                d.grid.n[0], d.grid.n[1], d.grid.n[2], problem.degree,
                static_cast<unsigned long long>(sol.n_dofs), sol.total_seconds, ranks);
    for (const FormulaComparison& fc : c.formulas)
      std::printf("    %-18s ||d s_zz||/||s_zz,FEM|| %.3f, mean lateral ratio %.3f (K0 %.3f)\n",
                  std::string(dem::name_of(fc.formula)).c_str(), fc.relative_l2[8], fc.mean_lateral_ratio,
                  c.k0);
    std::printf("  report: %s\n", (folder / "report.md").c_str());
  });
  return 0;
}

}  // namespace upgrain::coupling
