#include "coupling/studies/continuum/continuum_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "coupling/run/stop_request.h"
#include "coupling/studies/calibration/bed_calibration.h"
#include "coupling/studies/continuum/coarse_graining_study.h"
#include "coupling/studies/continuum/dem_fem_comparison.h"
#include "coupling/studies/continuum/strain_report.h"
#include "coupling/studies/continuum/study_report.h"
#include "coupling/studies/continuum/wall_shear_profile.h"
#include "coupling/studies/dem_run.h"
#include "coupling/studies/figure_script.h"
#include "dem/core/error.h"
#include "dem/core/out_of_memory.h"
#include "dem/files/atomic_file.h"
#include "dem/io/grid_stress_output.h"
#include "dem/stress/asymmetry.h"
#include "fem/elastic_column.h"
#include "fem/frictional_column.h"
#include "upscale/grid_fields.h"
#include "upscale/grid_mesh.h"

#ifndef UPGRAIN_SCRIPT_DIR
#define UPGRAIN_SCRIPT_DIR ""
#endif

namespace upgrain::coupling {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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
  int levels = static_cast<int>(d.wall_shear.size());
  MPI_Bcast(&levels, 1, MPI_INT, 0, comm);
  d.wall_shear.resize(static_cast<std::size_t>(levels));
  MPI_Bcast(d.wall_shear.data(), levels, MPI_DOUBLE, 0, comm);
}

// The one-mesh output: the DEM's formulas, each continuum's stress (the column on rollers
// with the DEM's difference from it) and the hydrostatic sigma_zz.
upscale::GridFields comparison_fields(const DemOutcome& d, const DemFemComparison& c,
                                      const std::vector<dem::StressFormula>& formulas) {
  upscale::GridFields f = upscale::grid_fields_from_stress(d.grid, d.stress, formulas);
  const int cells = d.grid.num_cells();
  const char* comp[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
  for (int e : {0, 4, 8, 1, 2, 5}) {
    for (const ContinuumResult& r : c.continua) {
      std::vector<double> v(cells);
      for (int k = 0; k < cells; ++k) v[k] = r.cells[k][e];
      f.add(r.key + "_s_" + comp[e], v);
    }
    const std::vector<Tensor9>& rollers = c.continua.front().cells;
    for (dem::StressFormula fm : formulas) {
      std::vector<double> diff(cells);
      for (int k = 0; k < cells; ++k) diff[k] = d.stress[fm][k](e / 3, e % 3) - rollers[k][e];
      f.add("diff_" + dem::io::field_name(fm) + "_s_" + comp[e], diff);
    }
  }
  f.add("analytic_s_zz", c.analytic_szz);
  return f;
}

ContinuumResult continuum_result(std::string key, std::string label,
                                 const std::vector<std::array<double, 9>>& cell_average_stress,
                                 double wall_share) {
  return {std::move(key),
          std::move(label),
          {cell_average_stress.begin(), cell_average_stress.end()},
          wall_share,
          0.0,
          {},
          {}};
}

// The continua's wall friction: Continuum/wall friction and floor friction, or with auto
// the coefficients the DEM applies (none when its wall friction is off). The container's
// walls are the floor, then x min, x max, y min, y max; the continuum's side walls have the
// same order.
fem::WallFriction wall_friction(const SceneInput& in) {
  const ContinuumOptions& o = in.study.continuum;
  const dem::SceneConfig& s = in.scene;
  const auto dem_friction = [&](int wall) {
    return s.effects.wall_friction ? s.container.friction[wall] : 0.0;
  };
  fem::WallFriction walls;
  for (int w = 0; w < 4; ++w) walls.side[w] = o.wall_friction.value_or(dem_friction(w + 1));
  walls.floor = o.floor_friction.value_or(dem_friction(0));
  return walls;
}

// The frictional continuum of one variant: the rollers column's box, mesh and elasticity, in
// a box whose walls have the friction the scene asks for (docs/study.md).
FrictionalRun frictional_run(const SceneInput& in, const fem::ColumnProblem& column,
                             ContinuumVariant variant) {
  const ContinuumOptions& o = in.study.continuum;
  FrictionalRun run;
  run.variant = variant;
  const bool plastic = variant == ContinuumVariant::drucker_prager;
  run.key = plastic ? "fem_drucker_prager" : "fem_elastic_friction";
  run.label = plastic ? "Drucker-Prager with wall friction" : "elastic with wall friction";
  fem::FrictionalColumnProblem& p = run.problem;
  p.column = column;
  p.material = plastic ? fem::ColumnMaterial::drucker_prager : fem::ColumnMaterial::elastic;
  p.strength = {o.friction_angle_deg, o.dilatancy_angle_deg, o.cohesion, o.cone_matching};
  p.walls = wall_friction(in);
  p.loading.load_steps = o.load_steps;
  p.loading.staged_construction = o.staged_construction;
  return run;
}

// Janssen for the continua's box: K = nu / (1 - nu), and the friction perimeter of the
// frictional continua's side walls (the walls x = const are Ly long, y = const Lx).
fem::JanssenColumn janssen_line(const fem::ColumnProblem& column,
                                const std::array<double, 4>& side_friction) {
  const double perimeter = (side_friction[0] + side_friction[1]) * column.length_y +
                           (side_friction[2] + side_friction[3]) * column.length_x;
  return {column.density * column.gravity, column.length_x * column.length_y, perimeter,
          fem::analytic_k0(column.poisson_ratio), column.height};
}

// Janssen's slab means on the grid: sigma_zz uniform over each level, sigma_xx = sigma_yy =
// K sigma_zz, no shear.
std::vector<std::array<double, 9>> janssen_cells(const fem::JanssenColumn& j, const dem::RegularGrid& g) {
  std::vector<std::array<double, 9>> cells(g.num_cells());
  const double dz = (g.hi.z() - g.lo.z()) / g.n[2];
  for (int cell = 0; cell < g.num_cells(); ++cell) {
    const int k = cell / (g.n[0] * g.n[1]);
    const double szz = j.mean_vertical_stress(k * dz, (k + 1) * dz);
    cells[cell] = {j.lateral_ratio * szz, 0, 0, 0, j.lateral_ratio * szz, 0, 0, 0, szz};
  }
  return cells;
}

// The study's own calibration (docs/calibration.md) on the bed of its DEM run, with the scene's
// Calibration section; its values become the Continuum entries of `in`, named as the
// calibration's (ContinuumOptions::source_of). A calibration whose fits give no material the
// continua take is refused with Continuum/material from = calibration, and leaves the entries in
// place, with a warning and the reason in the report, with auto.
BedCalibration calibrate_continuum(SceneInput& in, RunResult& r, MPI_Comm comm,
                                   const std::function<void(const Progress&)>& on_progress) {
  on_rank0(comm, [&] {
    std::printf(
        "  calibration of the continua on this bed (Continuum/material from): oedometric and friction-angle "
        "tests (docs/calibration.md)\n");
    std::fflush(stdout);
  });
  const dem::EngineState none;
  BedCalibration b;
  try {
    // By gravity the bed keeps its walls: lubricated, a bed deposited and relaxed between walls
    // with friction settles (docs/calibration.md, "By gravity"). The lid seats on and compacts
    // the bed's top anyway, in the lubricated ring.
    CalibrationOptions own_bed = in.calibration;
    own_bed.lubricate_side_walls = in.calibration.oedometer_by_lid;
    b = calibrate_bed(in.scene, r.final_state ? *r.final_state : none, own_bed, cell_servo_of(in), comm,
                      engine_options(in), on_progress);
  } catch (const RunStopped& e) {
    throw RunStopped(
        e.signal(), e.step(), {},
        "during the calibration of the continua on the bed, which is not checkpointed: the DEM "
        "run's output in " +
            in.output.folder.string() +
            " is complete, the continua and the report are not written; run the study again (with "
            "Output/overwrite = "
            "true, or into another folder), or "
            "set Continuum/material from = entries, or name an earlier calibration's material.prm as "
            "Continuum/material file");
  }
  r.final_state.reset();
  const std::filesystem::path cal = std::filesystem::path(in.output.folder) / "calibration";
  on_rank0(comm, [&] {
    write_bed_calibration(cal, in.source, b);
    std::printf("\n  ");
    print_bed_calibration(b);
  });
  // The figures are the same bits on every rank: so is this decision.
  ContinuumOptions& c = in.study.continuum;
  if (const std::string why = b.material_error(cal); !why.empty()) {
    if (c.material_from == ContinuumOptions::MaterialSource::calibration)
      throw CollectiveError("Continuum/material from = calibration: the calibration of the bed failed: " +
                            why);
    c.calibrate_in_study = false;
    c.calibration_skipped = "the calibration of the bed failed (" + why + ")";
    on_rank0(comm, [&] {
      std::printf("  warning: %s; the continua take the Continuum entries\n", c.calibration_skipped.c_str());
    });
    return b;
  }
  c.youngs_modulus = b.elastic.youngs;
  c.poisson_ratio = b.elastic.poisson;
  c.friction_angle_deg = b.friction_angle;
  c.dilatancy_angle_deg = b.dilatancy_angle;
  c.material_file = (cal / "material.prm").string();
  c.material_file_entries = {"youngs modulus", "poisson ratio", "friction angle", "dilatancy angle"};
  c.calibrated = true;
  on_rank0(comm, [&] {
    std::printf(
        "  continuum material from this bed: E %.9g Pa, nu %.9g, friction angle %.9g deg, dilatancy angle "
        "%.9g deg (%s; reuse it with Continuum/material file)\n",
        c.youngs_modulus, c.poisson_ratio, c.friction_angle_deg, c.dilatancy_angle_deg,
        c.material_file.c_str());
  });
  return b;
}

// The DEM-vs-continuum study proper: the chain above, from the DEM run to the report.
int run_comparison(const SceneInput& scene_input, MPI_Comm comm,
                   const std::function<void(const Progress&)>& on_progress,
                   const std::function<void(const RunResult&)>& on_dem_done) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  // The study's input; its Continuum entries take the calibration's values below.
  SceneInput in = scene_input;
  in.control.keep_final_state = in.study.continuum.calibrate_in_study;
  in.control.keep_wall_contacts = true;
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
    if (r.side_wall_contacts)
      d.wall_shear = dem_wall_shear(*r.side_wall_contacts, grid_levels(d.grid), box_perimeter(in.scene));
  });
  // A resumed run's earlier segments count in its stage and in the whole study (rank 0's
  // figure; run_history.h).
  const double earlier = r.wall_seconds - r.segment_seconds;
  timings.emplace_back("DEM deposition, relaxation and grid stress (" + std::to_string(ranks) + " rank" +
                           (ranks > 1 ? "s, " : ", ") + dem::to_string(in.parallel.summation) + " summation" +
                           (r.history.resumed_at.empty() ? "" : ", every segment") + ")",
                       earlier + since(t0));
  broadcast(d, comm);

  // 1b. The continua's material measured on this bed (Continuum/material from; docs/study.md).
  std::optional<BedCalibration> calibration;
  if (in.study.continuum.calibrate_in_study) {
    calibration = calibrate_continuum(in, r, comm, on_progress);
    timings.emplace_back("calibration of the continua on the bed: oedometric test",
                         calibration->oedometer_seconds);
    timings.emplace_back("calibration of the continua on the bed: friction-angle test",
                         calibration->triaxial_seconds);
  }

  // 2. The continua of the same container, filled to the grid's top: the elastic column on
  // rollers, each frictional variant, and Janssen's line.
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
  problem.keep_quadrature_stress = in.output.coarse_graining.enabled;
  const fem::ColumnSolution sol = allocating("the elastic continuum's mesh and system (FEM)", [&] {
    return fem::solve_column(problem, comm, (folder / "fem").string());
  });
  timings.emplace_back("continuum: elastic on rollers (FEM, output included)", since(t0));
  std::vector<ContinuumResult> continua = {
      continuum_result("fem", "elastic on rollers", sol.cell_average_stress, 0.0)};
  std::vector<FrictionalRun> frictional;
  std::vector<std::pair<std::string, std::string>> failed;  // label, why
  for (const ContinuumVariant variant : in.study.continuum.variants) {
    t0 = Clock::now();
    FrictionalRun run = frictional_run(in, problem, variant);
    try {
      run.solution = allocating("a frictional continuum's mesh and system (FEM)", [&] {
        return fem::solve_frictional_column(run.problem, comm, (folder / run.key).string());
      });
    } catch (const fem::NewtonFailure& e) {
      // Every rank throws alike (the decision rests on reduced residuals). The DEM run and
      // the other continua are kept; the report says what failed.
      failed.emplace_back(run.label, e.what());
      on_rank0(comm, [&] {
        std::printf("  warning: %s left out of the study: %s\n", run.label.c_str(), e.what());
      });
      continue;
    }
    timings.emplace_back("continuum: " + run.label + " (FEM, output included)", since(t0));
    continua.push_back(continuum_result(run.key, run.label, run.solution.cell_average_stress,
                                        run.solution.side_wall_vertical_force / run.solution.weight));
    continua.back().wall_shear = wall_shear_of_forces(run.solution.side_wall_vertical_force_by_level,
                                                      grid_levels(d.grid), box_perimeter(in.scene));
    frictional.push_back(std::move(run));
  }
  const fem::JanssenColumn janssen = janssen_line(problem, wall_friction(in).side);
  continua.front().wall_shear.assign(static_cast<std::size_t>(d.grid.n[2]), 0.0);  // rollers: none
  continua.push_back(
      continuum_result("janssen", "Janssen", janssen_cells(janssen, d.grid), janssen.wall_share()));
  // Janssen's column starts at z = 0, as the continua's.
  continua.back().wall_shear =
      janssen_wall_shear(janssen, {0.0, problem.height / d.grid.n[2], d.grid.n[2]}, box_perimeter(in.scene));

  // 3. Comparison and the one-mesh output.
  t0 = Clock::now();
  const double weight = d.total_mass * in.scene.gravity;
  DemFemComparison c = compare_dem_fem(d.grid, d.stress, std::move(continua), fem::analytic_solution(problem),
                                       -d.side_wall_vertical / weight + 0.0, in.study.formulas);
  c.dem_wall_shear = d.wall_shear;
  upscale::UpscaleOptions uo;
  uo.refinements = 0;
  (void)upscale::upscale_to_mesh(comparison_fields(d, c, in.study.formulas), comm, folder / "mesh", "dem_fem",
                                 uo);
  timings.emplace_back("comparison and upscaling to the mesh", since(t0));
  CoarseGrainingOutcome cg;
  if (in.output.coarse_graining.enabled) {
    t0 = Clock::now();
    cg = allocating("the coarse-grained fields on the mesh",
                    [&] { return coarse_grain_on_mesh(in, r, problem, sol, comm, folder); });
    timings.emplace_back("coarse-grained fields on the mesh", since(t0));
  }

  // 4. Tables, plots and the report (rank 0).
  on_rank0(comm, [&] {
    t0 = Clock::now();
    write_comparison_tables(folder, c, d.stress);
    const std::vector<std::string> plots =
        run_figure_script(
            "studies/continuum/plot_study.py", folder, "plots.log",
            {"profiles_szz.png", "lateral_ratio.png", "wall_share.png", "wall_shear.png", "level_spread.png"})
            .made;
    std::vector<std::string> strain_plots;
    if (r.final_strain) {
      (void)write_strain_mesh(folder);
      strain_plots = plot_strain(folder);
    }
    timings.emplace_back("tables and plots", since(t0));
    timings.emplace_back("whole study", earlier + since(t_all));
    const StudyRecord record{in, r,       d,     problem,      sol,   frictional, failed,     janssen,
                             c,  timings, plots, strain_plots, ranks, cg,         calibration};
    write_report(folder, record);
    write_study_json(folder, record);
    std::printf("  study: %d x %d x %d grid, continua Q%u with %llu dofs: elastic on rollers %.2f s",
                d.grid.n[0], d.grid.n[1], d.grid.n[2], problem.degree,
                static_cast<unsigned long long>(sol.n_dofs), sol.total_seconds);
    for (const FrictionalRun& f : frictional)
      std::printf(", %s %.2f s (%u Newton iterations)", f.label.c_str(), f.solution.total_seconds,
                  f.solution.newton_iterations);
    std::printf("; %d rank(s)\n", ranks);
    for (const FormulaComparison& fc : c.formulas)
      std::printf(
          "    %-18s closest continuum: %s, ||d s|| / ||s_zz,hydrostatic|| %.3f (elastic on rollers %.3f), "
          "mean lateral ratio %.3f (K0 %.3f)\n",
          std::string(dem::name_of(fc.formula)).c_str(), c.continua[fc.closest].label.c_str(),
          fc.against[fc.closest].tensor, fc.against[0].tensor, fc.mean_lateral_ratio, c.k0);
    std::printf("  side walls carry: DEM %.1f %%", 100.0 * c.dem_wall_share);
    for (const ContinuumResult& cr : c.continua)
      std::printf(", %s %.1f %%", cr.label.c_str(), 100.0 * cr.wall_share);
    std::printf("\n");
    if (cg.done)
      std::printf(
          "    coarse-grained (%s, w = %.3g d) ||d s_zz||/||s_zz,FEM|| %.3f over the mesh; momentum balance "
          "residual %.2e of rho g (d(rho v)/dt %.2e), %lu %s, %.2f s\n",
          cg.kernel.c_str(), cg.width_in_diameters,
          cg.comparison.l2_difference[8] / cg.comparison.l2_continuum_zz, cg.residual, cg.momentum_rate,
          cg.comparison.points, cg.points.c_str(), cg.seconds);
    std::printf("  report: %s\n", (folder / "report.md").c_str());
  });
  return 0;
}

}  // namespace

int run_continuum_study(const SceneInput& in, MPI_Comm comm, const StudyHooks& hooks) {
  if (in.study.compare_with_continuum) return run_comparison(in, comm, hooks.progress, hooks.dem_done);
  // The DEM alone: with strain, the strain on the mesh and report.md with its section and plots.
  const RunResult r = run_dem(in, comm, hooks.progress);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) {
    if (hooks.dem_done) hooks.dem_done(r);
    if (r.final_strain) {
      (void)write_strain_mesh(in.output.folder);
      write_run_report(in.output.folder, in, r, plot_strain(in.output.folder));
      std::printf("  report: %s\n", (in.output.folder / "report.md").c_str());
    }
  }
  return 0;
}

}  // namespace upgrain::coupling
