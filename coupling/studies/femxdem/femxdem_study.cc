#include "coupling/studies/femxdem/femxdem_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "coupling/femxdem/rve_packings.h"
#include "coupling/femxdem/rve_point.h"
#include "coupling/studies/dem_run.h"
#include "coupling/studies/femxdem/cell_snapshots.h"
#include "coupling/studies/femxdem/femxdem_checkpoints.h"
#include "coupling/studies/figure_script.h"
#include "coupling/studies/report_format.h"
#include "dem/files/atomic_file.h"
#include "dem/files/json_number.h"
#include "dem/scene/effect_choice.h"
#include "dem/scene/weight_overlap.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The platen's mean axial stress, compression positive: its reaction per unit thickness over
// the width.
double axial_stress(const fem::LoadStepRecord& s, const FemxdemOptions& o) {
  return -s.platen_force / o.width;
}

std::string load_displacement_table(const std::vector<fem::LoadStepRecord>& steps, const FemxdemOptions& o) {
  std::ostringstream t;
  t << "# Upgrain FEM x DEM biaxial compression (docs/femxdem.md). SI units, compression positive. "
       "axial_strain = -platen displacement / height; sigma_1 = the top platen's reaction per unit "
       "thickness over the width; sigma_3 = the confining pressure; newton_iterations summed over the "
       "step's sub-steps; halvings = the line search's halvings of Newton corrections; grain_steps = the DEM "
       "cells' work (grain-steps, every rank); wall_s = the "
       "step's wall time (the slowest rank's); imbalance = the busiest rank's grain-steps over the ranks' "
       "mean in the step; repartitioned = 1 when the mesh was then repartitioned by the cells' cost\n"
       "step,platen_displacement,axial_strain,sigma_1,sigma_3,q,q_over_p,newton_iterations,cuts,"
       "halvings,grain_steps,wall_s,imbalance,repartitioned\n";
  const double s3 = o.rve.mean_stress;
  for (const fem::LoadStepRecord& s : steps) {
    const double s1 = axial_stress(s, o);
    const double p = (s1 + 2.0 * s3) / 3.0, q = s1 - s3;
    t << s.step << ',' << table_number(s.platen_displacement) << ','
      << table_number(0.0 - s.platen_displacement / o.height) << ',' << table_number(s1) << ','
      << table_number(s3) << ',' << table_number(q) << ',' << table_number(q / p) << ','
      << s.newton_iterations << ',' << s.cuts << ',' << s.line_search_halvings << ',' << table_number(s.cost)
      << ',' << table_number(s.seconds) << ',' << table_number(s.imbalance) << ','
      << (s.repartitioned ? 1 : 0) << '\n';
  }
  return t.str();
}

// The head of points.csv and point_history.csv: `what` says which steps the rows are of.
std::string points_head(const std::string& what, const std::vector<std::string>& measures) {
  std::string h =
      "# Upgrain FEM x DEM: every Gauss point's DEM cell " + what +
      " (docs/femxdem.md). SI units, tension positive; eps the small strain of the point's "
      "displacement gradient; p = -tr sigma / 3, q = sqrt(3/2) |dev sigma|; rotation the "
      "point's rigid rotation (H_yx - H_xy) / 2; then the cell's measures: solid_fraction, "
      "coordination (2 touching pairs per grain), grain_rotation (the grains' mean rotation about "
      "z, rad), held_steps and unbalanced_force (its last relaxation)\n"
      "step,cell,point,x,y,sigma_xx,sigma_yy,sigma_zz,sigma_xy,eps_xx,eps_yy,eps_xy,p,q,q_over_p,"
      "rotation";
  for (const std::string& m : measures) h += ',' + m;
  return h + '\n';
}

// One row a point.
std::string point_rows(unsigned step, const std::vector<fem::PointSummary>& points) {
  std::ostringstream t;
  for (const fem::PointSummary& s : points) {
    const fem::Mat3x3 sigma = fem::mandel::to_matrix(s.stress);
    const fem::Mat3x3& h = s.displacement_gradient;
    const fem::Mat3x3 eps = 0.5 * (h + h.transpose());
    const double p = -sigma.trace() / 3.0, q = std::sqrt(1.5) * fem::mandel::deviator(s.stress).norm();
    t << step << ',' << s.place.cell << ',' << s.place.index << ',' << table_number(s.place.position[0])
      << ',' << table_number(s.place.position[1]) << ',' << table_number(sigma(0, 0)) << ','
      << table_number(sigma(1, 1)) << ',' << table_number(sigma(2, 2)) << ',' << table_number(sigma(0, 1))
      << ',' << table_number(eps(0, 0)) << ',' << table_number(eps(1, 1)) << ',' << table_number(eps(0, 1))
      << ',' << table_number(p) << ',' << table_number(q) << ',' << table_number(p != 0.0 ? q / p : 0.0)
      << ',' << table_number(0.5 * (h(1, 0) - h(0, 1)));
    for (const double m : s.measures) t << ',' << table_number(m);
    t << '\n';
  }
  return t.str();
}

// One level of the column's Gauss points (those at one height), averaged across the width.
struct ColumnLevel {
  double y = 0.0;
  int points = 0;
  fem::Mat3x3 stress = fem::Mat3x3::Zero();
  double solid_fraction = 0.0, coordination = 0.0;
};

// The unit weight rho g of the column: its points' mean density (each cell's own) times gravity.
double column_unit_weight(const std::vector<fem::PointSummary>& points, const fem::QuasiStaticProblem& p) {
  double sum = 0.0;
  for (const fem::PointSummary& s : points) sum += s.density;
  return points.empty() ? 0.0 : sum / static_cast<double>(points.size()) * std::abs(p.gravity[1]);
}

std::vector<ColumnLevel> column_levels(const std::vector<fem::PointSummary>& points,
                                       const std::vector<std::string>& measures, double height) {
  const auto index_of = [&](const std::string& name) {
    for (std::size_t k = 0; k < measures.size(); ++k)
      if (measures[k] == name) return static_cast<int>(k);
    return -1;
  };
  const int phi = index_of("solid_fraction"), z = index_of("coordination");
  std::map<long long, ColumnLevel> by_height;  // keyed by the height in units of 1e-9 of the column's
  for (const fem::PointSummary& s : points) {
    ColumnLevel& l = by_height[std::llround(s.place.position[1] / height * 1e9)];
    l.y = s.place.position[1];
    ++l.points;
    l.stress += fem::mandel::to_matrix(s.stress);
    if (phi >= 0) l.solid_fraction += s.measures[static_cast<std::size_t>(phi)];
    if (z >= 0) l.coordination += s.measures[static_cast<std::size_t>(z)];
  }
  std::vector<ColumnLevel> levels;
  for (auto& [key, l] : by_height) {
    l.stress /= l.points;
    l.solid_fraction /= l.points;
    l.coordination /= l.points;
    levels.push_back(l);
  }
  std::reverse(levels.begin(), levels.end());  // from the top down
  return levels;
}

// The levels from the top at the load factor `lambda`, beside the weight's
// sigma_yy = -(p_top + lambda rho g (H - y)) (rho the points' mean density): what equilibrium gives
// whatever the material, smooth sides carrying nothing.
std::string column_table(const std::vector<ColumnLevel>& levels, double height, double top_pressure,
                         double unit_weight, double lambda) {
  std::ostringstream t;
  t << "# Upgrain FEM x DEM column under its own weight (docs/femxdem.md), at the last converged load "
       "step (the weight's fraction lambda = "
    << table_number(lambda)
    << "). SI units, tension positive. One row per level of Gauss points (averaged across the width), "
       "from the top; depth = height - y; weight_sigma_yy = -(top pressure + lambda rho g depth), the "
       "stress that equilibrium gives with smooth sides (rho the points' mean density); K0 = "
       "sigma_xx / sigma_yy; solid_fraction and coordination the cells'\n"
       "level,y,depth,points,sigma_xx,sigma_yy,sigma_zz,weight_sigma_yy,K0,solid_fraction,coordination\n";
  int k = 0;
  for (const ColumnLevel& l : levels) {
    const double depth = height - l.y;
    t << k++ << ',' << table_number(l.y) << ',' << table_number(depth) << ',' << l.points << ','
      << table_number(l.stress(0, 0)) << ',' << table_number(l.stress(1, 1)) << ','
      << table_number(l.stress(2, 2)) << ',' << table_number(-(top_pressure + lambda * unit_weight * depth))
      << ',' << table_number(l.stress(0, 0) / l.stress(1, 1)) << ',' << table_number(l.solid_fraction) << ','
      << table_number(l.coordination) << '\n';
  }
  return t.str();
}

}  // namespace

fem::QuasiStaticProblem femxdem_problem(const FemxdemOptions& o, double gravity) {
  fem::QuasiStaticProblem p;
  p.dimension = 2;
  p.size = {o.width, o.height, 1.0};
  p.cells = {static_cast<unsigned>(o.cells_x), static_cast<unsigned>(o.cells_y), 1};
  p.degree = static_cast<unsigned>(o.degree);
  p.quadrature_points = static_cast<unsigned>(o.quadrature_points);
  if (o.loading == FemxdemLoading::gravity_column) {
    p.faces[0].support = fem::FaceSupport::roller;
    p.faces[1].support = fem::FaceSupport::roller;
    p.faces[2].support = fem::FaceSupport::fixed;
    p.faces[3] = {fem::FaceSupport::pressure, o.rve.mean_stress};
    p.gravity = {0.0, -gravity, 0.0};
    p.body_force_follows_load = true;
  } else {
    p.faces[0] = {fem::FaceSupport::pressure, o.rve.mean_stress};
    p.faces[1] = {fem::FaceSupport::pressure, o.rve.mean_stress};
    p.faces[2].support = o.rough_platens ? fem::FaceSupport::fixed : fem::FaceSupport::roller;
    p.faces[3].support = o.rough_platens ? fem::FaceSupport::rough_platen : fem::FaceSupport::smooth_platen;
    p.platen_displacement = -o.axial_strain * o.height;
  }
  p.load_steps = static_cast<unsigned>(o.load_steps);
  p.residual_tolerance = o.residual_tolerance;
  p.correction_tolerance = o.correction_tolerance;
  p.max_newton_iterations = static_cast<unsigned>(o.max_newton_iterations);
  p.max_step_cuts = static_cast<unsigned>(o.max_step_cuts);
  p.line_search_halvings = static_cast<unsigned>(o.line_search_halvings);
  p.rebalance_threshold = o.rebalance_threshold;
  return p;
}

int run_femxdem_study(const SceneInput& in, MPI_Comm comm, const StudyHooks&) {
  const FemxdemOptions& o = in.femxdem;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const fs::path folder = fs::path(in.output.folder) / "femxdem";
  on_rank0(comm, [&] { dem::io::create_folder(folder); });

  // Every rank prepares the packings its points copy (deterministic, on MPI_COMM_SELF) rather than
  // receiving them; the first one on every rank, for the report.
  RvePackings packings(in.scene, o.rve, o.cell_packings);
  const auto prepared = packings.first();
  std::string effects;
  for (const dem::EffectChoice& c : dem::describe_effects(prepared->scene.effects))
    if (c.on) effects += (effects.empty() ? "" : ", ") + c.entry;
  if (rank == 0)
    std::printf(
        "  femxdem: the DEM cell: %ld grains, %ld contacts, p %.6g Pa, prepared in %ld steps (%.1f s); "
        "effects: %s%s\n",
        prepared->grains, prepared->contacts, -fem::mandel::trace(prepared->stress) / 3.0, prepared->steps,
        packings.preparation_seconds(), effects.empty() ? "none" : effects.c_str(),
        o.cell_packings == 1 ? ""
        : o.cell_packings == 0
            ? "; every Gauss point its own packing"
            : ("; one of " + std::to_string(o.cell_packings) + " packings at each Gauss point").c_str());

  // How far the cell's stress presses its grains into each other (dem/scene/weight_overlap.h): it
  // grows as p^(2/3) through the loading, and a cell whose largest overlap reaches the
  // runaway-overlap guard's limit refuses its trial.
  const double overlap = dem::stress_overlap_ratio(
      prepared->scene,
      {.pressure = -fem::mandel::trace(prepared->stress) / 3.0,
       .coordination = 2.0 * static_cast<double>(prepared->contacts) / static_cast<double>(prepared->grains),
       .solid_fraction = prepared->grain_volume / std::abs(prepared->reference_cell.determinant())});
  if (rank == 0)
    std::printf(
        "  femxdem: the cell's mean contact overlap %.3g of a radius at its pressure by the %s law%s\n",
        overlap, prepared->scene.contact_law.c_str(),
        overlap > dem::kStaticOverlapBound
            ? " (DEM keeps static overlaps below 0.01; it grows as the pressure's 2/3 power, and a cell "
              "whose largest overlap reaches 0.25 of a radius refuses its trial: stiffer grains, "
              "Particles/youngs modulus, keep the cells within the law)"
            : "");

  const bool column = o.loading == FemxdemLoading::gravity_column;
  fem::QuasiStaticProblem problem = femxdem_problem(o, in.scene.gravity);
  // The column's top carries the prepared cell's own vertical stress (within the servo's tolerance
  // of the confining pressure): the points' initial stresses are taken as balanced with it
  // (QuasiStaticProblem::body_force_follows_load), and column.csv's weight line starts from it.
  if (column) problem.faces[3].pressure = -fem::mandel::to_matrix(prepared->stress)(1, 1);
  // The tables so far, rewritten after each converged step: a run that stops keeps its path.
  std::vector<fem::LoadStepRecord> steps;
  std::string history;
  // The step's line: the platen's stress, or the column's deepest level.
  const auto on_points = [&](const fem::LoadStepRecord& s, const std::vector<std::string>& measures,
                             const std::vector<fem::PointSummary>& points) {
    if (rank != 0) return;
    steps.push_back(s);
    history += point_rows(s.step, points);
    std::string state;
    char line[160];
    if (column) {
      const double lambda = static_cast<double>(s.step) / problem.load_steps;
      const std::vector<ColumnLevel> levels = column_levels(points, measures, o.height);
      dem::io::write_text_atomically(folder / "column.csv",
                                     column_table(levels, o.height, problem.faces[3].pressure,
                                                  column_unit_weight(points, problem), lambda));
      const ColumnLevel& deepest = levels.back();
      std::snprintf(line, sizeof line, "weight %3.0f %%  deepest level: sigma_yy %.6g Pa  K0 %.4f",
                    100.0 * lambda, deepest.stress(1, 1), deepest.stress(0, 0) / deepest.stress(1, 1));
    } else {
      dem::io::write_text_atomically(folder / "load_displacement.csv", load_displacement_table(steps, o));
      std::snprintf(line, sizeof line, "eps_a %.4f  sigma_1 %.6g Pa", 0.0 - s.platen_displacement / o.height,
                    axial_stress(s, o));
    }
    dem::io::write_text_atomically(folder / "point_history.csv",
                                   points_head("at every load step", measures) + history);
    std::printf(
        "  femxdem: step %u/%u  %s  Newton %u  cuts %u  halvings %u  %.3g grain-steps  imbalance %.2f%s  "
        "%.1f s\n",
        s.step, problem.load_steps, line, s.newton_iterations, s.cuts, s.line_search_halvings, s.cost,
        s.imbalance, s.repartitioned ? " (repartitioned)" : "", s.seconds);
    std::fflush(stdout);
  };
  CellSnapshots snapshots(parse_cell_snapshots(o.cell_snapshots), folder, prepared->grains, comm);
  const fem::QuasiStaticOutput output{
      folder.string(), "femxdem", nullptr, on_points,
      [&](const fem::LoadStepRecord& s,
          const std::vector<std::pair<fem::PointPlace, const fem::PointState*>>& owned) {
        snapshots.write(s, owned);
      }};
  // The point history so far is kept with each checkpoint; load_displacement.csv is made again
  // from the solver's steps.
  FemxdemCheckpoints checkpoints(in, comm);
  const fem::QuasiStaticCheckpoints saving = checkpoints.for_solver(
      [&] { return history; },
      [&](const std::vector<fem::LoadStepRecord>& before, const std::string& tables) {
        snapshots.resumed(before);
        if (rank != 0) return;
        steps = before;
        history = tables;
        std::printf("  femxdem: resumed after load step %u of %u (eps_a %.4f)\n", before.back().step,
                    problem.load_steps, 0.0 - before.back().platen_displacement / o.height);
      });
  const RveOptions rve = o.rve;
  const auto t1 = std::chrono::steady_clock::now();
  const fem::QuasiStaticResult r = fem::solve_quasi_static(
      problem,
      [&](const fem::PointPlace& place) {
        return std::make_unique<RveCell>(
            RveSource{[&packings, place] { return packings.for_point(place); },
                      [&packings, place] { return packings.frame_for_point(place); }},
            rve);
      },
      comm, output, saving);
  const double solve_seconds = seconds_since(t1);
  // Every packing's preparation, on the rank that spent the most; those that a point first needed
  // inside the solve are also part of solve_s. A point that moved to another rank, or was resumed,
  // brought its packing in its bytes and prepared nothing.
  const double preparation_seconds = [&] {
    double s = packings.preparation_seconds(), most = 0.0;
    MPI_Allreduce(&s, &most, 1, MPI_DOUBLE, MPI_MAX, comm);
    return most;
  }();
  long packings_prepared = static_cast<long>(packings.prepared());
  MPI_Allreduce(MPI_IN_PLACE, &packings_prepared, 1, MPI_LONG, MPI_SUM, comm);

  on_rank0(comm, [&] {
    dem::io::write_text_atomically(
        folder / "points.csv",
        points_head("at the last load step", r.measure_names) + point_rows(r.steps.back().step, r.points));
    using dem::io::json_number;
    double grain_steps = 0.0, busiest = 0.0, solved_grain_steps = 0.0;
    unsigned iterations = 0, repartitions = 0, halvings = 0;
    for (const fem::LoadStepRecord& s : r.steps) {
      grain_steps += s.cost;
      // The throughput of this run's solve: a restart's steps only.
      if (static_cast<long>(s.step) > checkpoints.resumed_after()) solved_grain_steps += s.cost;
      busiest += s.cost * s.imbalance;
      iterations += s.newton_iterations;
      halvings += s.line_search_halvings;
      repartitions += s.repartitioned ? 1 : 0;
    }
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    std::ostringstream j;
    j << "{\n  \"study\": \"femxdem\",\n  \"ranks\": " << ranks << ",\n  \"cells\": " << r.n_cells
      << ",\n  \"gauss_points\": " << r.points.size() << ",\n  \"dofs\": " << r.n_dofs
      << ",\n  \"grains_per_cell\": " << prepared->grains << ",\n  \"cell_contacts\": " << prepared->contacts
      << ",\n  \"cell_packings\": " << o.cell_packings << ",\n  \"preparation_steps\": " << prepared->steps
      << ",\n  \"packings_prepared\": " << packings_prepared
      << ",\n  \"preparation_s\": " << json_number(preparation_seconds)
      << ",\n  \"solve_s\": " << json_number(solve_seconds) << ",\n  \"resumed_after_step\": "
      << (checkpoints.resumed_after() < 0 ? std::string("null") : std::to_string(checkpoints.resumed_after()))
      << ",\n  \"load_steps\": " << r.steps.size() - 1 << ",\n  \"newton_iterations\": " << iterations
      << ",\n  \"line_search_halvings\": " << halvings << ",\n  \"grain_steps\": " << json_number(grain_steps)
      << ",\n  \"grain_steps_per_core_second\": " << json_number(solved_grain_steps / (solve_seconds * ranks))
      << ",\n  \"imbalance\": " << json_number(grain_steps > 0.0 ? busiest / grain_steps : 1.0)
      << ",\n  \"repartitions\": " << repartitions << ",\n  \"loading\": \""
      << (column ? "gravity column" : "biaxial") << '"';
    if (column) {
      const std::vector<ColumnLevel> levels = column_levels(r.points, r.measure_names, o.height);
      j << ",\n  \"deepest_sigma_yy_Pa\": " << json_number(levels.back().stress(1, 1))
        << ",\n  \"deepest_K0\": " << json_number(levels.back().stress(0, 0) / levels.back().stress(1, 1));
    } else {
      j << ",\n  \"final_axial_stress_Pa\": " << json_number(axial_stress(r.steps.back(), o));
    }
    j << "\n}\n";
    dem::io::write_text_atomically(fs::path(in.output.folder) / "summary.json", j.str());
    run_figure_script("studies/femxdem/plot_femxdem.py", folder, "plots.log",
                      {column ? "column.png" : "load_displacement.png", "points.png"});
    std::printf(
        "  femxdem: %zu Gauss points, %u Newton iterations, %.3g grain-steps in %.1f s (%.3g per "
        "core-second)\n",
        r.points.size(), iterations, solved_grain_steps, solve_seconds,
        solved_grain_steps / (solve_seconds * ranks));
  });
  return 0;
}

}  // namespace upgrain::coupling
