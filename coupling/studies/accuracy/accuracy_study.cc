#include "coupling/studies/accuracy/accuracy_study.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include "coupling/studies/accuracy/accuracy_knobs.h"
#include "coupling/studies/accuracy/bed_measures.h"
#include "coupling/studies/accuracy/collision_reference.h"
#include "coupling/studies/accuracy/contact_solver_reference.h"
#include "coupling/studies/dem_run.h"
#include "coupling/studies/figure_script.h"
#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/parallel/exchange.h"
#include "dem/time_step.h"
#include "fem/elastic_column.h"

#ifndef UPGRAIN_SCRIPT_DIR
#define UPGRAIN_SCRIPT_DIR ""
#endif

namespace upgrain::coupling {

namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One setting's results.
struct Row {
  const KnobSetting* setting = nullptr;  // null for the reference and its replicas
  std::string knob = "reference", label;
  bool is_default = false;
  double wall_seconds = kNaN;
  BedMeasures bed;
  bool has_bed = false;
  std::vector<double> change;  // against the reference (bed_measures.h)
  double exact_error = kNaN;   // against the exact answer, when one exists
  std::string exact_name;
  double point_szz = kNaN;  // grid knob: sigma_zz at the centre of the bed
  // Steps of the run: the dynamics (to the end time or rest) and FIRE's, which a relaxation
  // that does not reach its tolerance ends at its step limit.
  long steps = 0, fire_steps = 0;
  bool fire_converged = true;
};

std::string slug(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

std::string fmt(double v, const char* f = "%.3g") {
  if (!std::isfinite(v)) return "-";
  char b[48];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// sigma_zz (Bagi) of the cell that holds the centre of the bed.
double centre_szz(const RunResult& r, const SceneInput& in, double height) {
  if (!r.final_stress) return kNaN;
  const int c =
      r.final_grid.cell_of(dem::Vec3(0.5 * in.scene.container.lx, 0.5 * in.scene.container.ly, 0.5 * height));
  return c < 0 ? kNaN : (*r.final_stress)[dem::StressFormula::bagi][c](2, 2);
}

class AccuracyStudy {
 public:
  AccuracyStudy(const SceneInput& in, MPI_Comm comm)
      : in_(in), comm_(comm), folder_(in.output.folder / "accuracy") {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &ranks_);
  }

  int run() {
    settings_ = knob_settings(in_, in_.accuracy, ranks_, skipped_);
    on_root([&] { dem::io::create_folder(folder_ / "runs"); });
    const int replicas = std::max(1, in_.accuracy.replicas);
    total_runs_ = replicas;
    for (const KnobSetting& s : settings_)
      if (!s.is_default || s.run != SettingRun::dem) ++total_runs_;
    // The reference and its replicas: the noise floor.
    for (int k = 0; k < replicas; ++k) {
      Row r;
      r.label = k == 0 ? "the scene as given"
                       : "replica " + std::to_string(k) + " (fill seed + " + std::to_string(k) + ")";
      r.is_default = k == 0;
      SceneInput in = in_;
      in.scene.fill.seed += static_cast<std::uint64_t>(k);
      dem_row(in, r, false, "reference_" + std::to_string(k));
      (k == 0 ? reference_ : replicas_.emplace_back()) = r;
    }
    reference_.change =
        rank_ == 0 ? changes(reference_.bed, reference_.bed) : std::vector<double>(kMeasures, kNaN);
    noise_.assign(kMeasures, 0.0);
    for (Row& r : replicas_) {
      r.change = rank_ == 0 ? changes(reference_.bed, r.bed) : std::vector<double>(kMeasures, kNaN);
      for (int m = 0; m < kMeasures; ++m)
        if (std::isfinite(r.change[m])) noise_[m] = std::max(noise_[m], r.change[m]);
    }
    for (const KnobSetting& s : settings_) rows_.push_back(evaluate(s));
    int code = 0;
    on_root([&] { code = write(); });
    MPI_Bcast(&code, 1, MPI_INT, 0, comm_);
    return code;
  }

 private:
  void on_root(const std::function<void()>& work) const { dem::run_on_root(comm_, work); }

  // A DEM run of `in` into runs/<name>/, its wall time (the slowest rank's) and its measures.
  void dem_row(SceneInput in, Row& row, bool one_rank, const std::string& name) {
    in.output.folder = folder_ / "runs" / name;
    in.output.snapshot_interval = 0.0;  // the first and the last: the runs' time is the physics'
    in.output.checkpoint.interval = in.output.checkpoint.wall_interval = 0.0;
    in.overwrite = true;
    in.study.compare_with_continuum = false;  // the DEM alone: the continuum has its own knob
    in.use = StudyUse{};                      // a plain run of the scene, its knobs checked already
    in.restarting = false;
    in.resume.reset();
    validate_scene(in);
    progress(row);
    RunResult r;
    double seconds = 0.0;
    if (one_rank) {
      if (rank_ == 0) {
        const double t0 = MPI_Wtime();
        r = run_dem(in, MPI_COMM_SELF, {});
        seconds = MPI_Wtime() - t0;
      }
    } else {
      const double t0 = MPI_Wtime();
      r = run_dem(in, comm_, {});
      seconds = MPI_Wtime() - t0;
      MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, comm_);
    }
    row.wall_seconds = seconds;
    if (rank_ == 0) {
      row.bed = measure(r, in.scene.particles.count, in.scene.effects.gravity ? in.scene.gravity : 0.0);
      row.has_bed = true;
      row.point_szz = centre_szz(r, in, row.bed.height);
      row.fire_steps = r.relaxation ? r.relaxation->steps : 0;
      row.fire_converged = !r.relaxation || r.relaxation->converged;
      row.steps = r.steps - row.fire_steps;
    }
    done_seconds_ += seconds;
    ++done_runs_;
  }

  Row evaluate(const KnobSetting& s) {
    Row row = reference_;
    row.setting = &s;
    row.knob = s.knob;
    row.label = s.label;
    row.is_default = s.is_default;
    row.exact_error = kNaN;
    if (s.run == SettingRun::fem) {
      fem_row(s, row);
    } else if (!(s.is_default && s.run == SettingRun::dem)) {
      SceneInput in = in_;
      s.apply(in);
      dem_row(in, row, s.run == SettingRun::dem_one_rank,
              std::to_string(done_runs_) + "_" + slug(s.knob + " " + s.label));
    }
    row.change =
        rank_ == 0 && row.has_bed ? changes(reference_.bed, row.bed) : std::vector<double>(kMeasures, kNaN);
    if (s.knob == "time step" && rank_ == 0) {
      // The exact reference: the collision at this step (the step of the changed scene).
      SceneInput in = in_;
      s.apply(in);
      const dem::TimeStepEstimate ts = dem::estimate_time_step(in.scene);
      const CollisionError e = collision_error(in.scene, in.scene.particles.radius,
                                               std::max(ts.impact_speed, 0.1), in.scene.time_step);
      row.exact_error = std::max(e.duration, e.restitution);
      row.exact_name = "Hertz collision: contact duration and restitution (" +
                       fmt(e.steps_in_contact, "%.0f") + " steps in contact)";
    }
    if ((s.knob == "solver tolerance" || s.knob == "solver iterations") && rank_ == 0) {
      // The exact reference: contacts of known depth, solved with the changed settings.
      SceneInput in = in_;
      s.apply(in);
      const ContactSolverError e = contact_solver_error(in.scene, in.scene.contact_solver);
      row.exact_error = e.depth;
      row.exact_name = "constructed contacts (long double), largest depth error " + fmt(e.depth, "%.2e") +
                       " c over " + std::to_string(e.pairs) + " cold and " + std::to_string(e.pairs) +
                       " warm solves; largest normal error " + fmt(e.normal, "%.1e") + " rad; Newton steps " +
                       fmt(e.cold_iterations, "%.2f") + " cold, " + fmt(e.warm_iterations, "%.2f") +
                       " warm; " + fmt(e.cold_ns, "%.0f") + " / " + fmt(e.warm_ns, "%.0f") +
                       " ns per solve; " + std::to_string(e.failures) + " not converged";
    }
    return row;
  }

  void fem_row(const KnobSetting& s, Row& row) {
    fem::ColumnProblem p;
    p.length_x = in_.scene.container.lx;
    p.length_y = in_.scene.container.ly;
    p.height = rank_ == 0 ? reference_.bed.height : 0.0;
    MPI_Bcast(&p.height, 1, MPI_DOUBLE, 0, comm_);
    p.density = in_.scene.particles.material.density * 0.6;
    p.gravity = in_.scene.gravity;
    p.youngs_modulus = in_.study.continuum.youngs_modulus;
    p.poisson_ratio = in_.study.continuum.poisson_ratio;
    for (int d = 0; d < 3; ++d) p.cells[d] = static_cast<unsigned>(in_.output.grid_stress.cells[d]);
    p.degree = s.fem_degree;
    p.refinements = s.fem_refinements;
    progress(row);
    const double t0 = MPI_Wtime();
    const fem::ColumnSolution sol = fem::solve_column(p, comm_, "");
    row.wall_seconds = MPI_Wtime() - t0;
    MPI_Allreduce(MPI_IN_PLACE, &row.wall_seconds, 1, MPI_DOUBLE, MPI_MAX, comm_);
    row.has_bed = false;
    row.change.assign(kMeasures, kNaN);
    row.exact_error = sol.l2_error_stress / fem::analytic_solution(p).stress_l2_norm(p.length_x * p.length_y);
    row.exact_name = "analytic column: relative L2 error of the stress";
    done_seconds_ += row.wall_seconds;
    ++done_runs_;
  }

  void progress(const Row& row) const {
    if (rank_ != 0) return;
    const double per_run = done_runs_ > 0 ? done_seconds_ / done_runs_ : 0.0;
    std::printf("  accuracy: run %d of %d: %s, %s (%.0f s so far, about %.0f s left)\n", done_runs_ + 1,
                total_runs_, row.knob.c_str(), row.label.c_str(), done_seconds_,
                per_run * (total_runs_ - done_runs_));
    std::fflush(stdout);
  }

  // Whether every change of `r` stays within the tolerance or the noise.
  bool within(const Row& r) const {
    for (int m = 0; m < kMeasures; ++m)
      if (std::isfinite(r.change[m]) && r.change[m] > std::max(in_.accuracy.tolerance, noise_[m]))
        return false;
    return true;
  }
  // Whether a row counts as within tolerance: its bed's changes, or, for a row without a bed
  // (the continuum's), its error against the exact answer.
  bool acceptable(const Row& r) const {
    return r.has_bed ? within(r) : (!std::isfinite(r.exact_error) || r.exact_error <= in_.accuracy.tolerance);
  }
  double worst_change(const Row& r) const {
    double w = kNaN;
    for (int m = 0; m < kMeasures - 1; ++m)  // the balance error is a quality, not a change of the bed
      if (std::isfinite(r.change[m])) w = std::isfinite(w) ? std::max(w, r.change[m]) : r.change[m];
    return w;
  }
  std::string change_text(const Row& r, int m) const {
    if (!std::isfinite(r.change[m])) return "-";
    // The balance error is a quality of the run: its own value, not its change.
    if (m == kMeasures - 1) return fmt(r.bed.balance_error, "%.2e");
    if (r.change[m] <= noise_[m]) return r.change[m] == 0.0 ? "0" : "no measurable change";
    return m == kMeasures - 1 ? fmt(r.change[m], "%.2e") : fmt(100.0 * r.change[m], "%.2f %%");
  }

  int write() {
    int code = 0;
    std::ostringstream csv;
    csv << "# Upgrain accuracy study. wall_s: wall time of the whole run on this machine; changes are "
           "relative "
           "to the scene as given (balance_error: absolute), noise = the largest change among replicas that "
           "differ "
           "only in the fill's seed\n";
    csv << "knob,setting,value,default,wall_s,time_ratio,steps,fire_steps,fire_converged,worst_change,"
           "within_tolerance,exact_error";
    for (const char* n : kMeasureNames) csv << ',' << n << ',' << n << "_change";
    csv << ",centre_szz\n";
    auto csv_row = [&](const Row& r, double value) {
      // A row without a bed (the continuum's) has no DEM steps: its step columns stay empty.
      const std::string steps = r.has_bed ? std::to_string(r.steps) + ',' + std::to_string(r.fire_steps) +
                                                ',' + (r.fire_converged ? "1" : "0")
                                          : std::string(",,");
      csv << r.knob << ",\"" << r.label << "\"," << value << ',' << (r.is_default ? 1 : 0) << ','
          << r.wall_seconds << ',' << r.wall_seconds / reference_.wall_seconds << ',' << steps << ','
          << worst_change(r) << ',' << (acceptable(r) ? 1 : 0) << ',' << r.exact_error;
      const std::vector<double> v = r.has_bed ? values(r.bed) : std::vector<double>(kMeasures, kNaN);
      for (int m = 0; m < kMeasures; ++m)
        csv << ',' << v[m] << ',' << (r.change.empty() ? kNaN : r.change[m]);
      csv << ',' << r.point_szz << '\n';
    };
    csv_row(reference_, 0.0);
    for (const Row& r : replicas_) csv_row(r, 0.0);
    for (const Row& r : rows_) csv_row(r, r.setting->value);
    dem::io::write_text_atomically(folder_ / "accuracy.csv", csv.str());

    std::ostringstream md;
    md << "# Accuracy study\n\n"
       << "Scene: `" << in_.source << "`, " << in_.scene.particles.count << " grains, run on " << ranks_
       << " MPI rank" << (ranks_ > 1 ? "s" : "") << ". Each row is a whole run of the scene with one setting "
       << "changed; times are wall times of whole runs on this machine, and their ratios to the scene as "
          "given "
       << "carry the message. Changes are relative to the scene as given; below the noise floor (the largest "
       << "change among " << replicas_.size()
       << " replicas that differ only in the fill's seed) a change reads "
       << "\"no measurable change\". Tolerance: " << fmt(100.0 * in_.accuracy.tolerance)
       << " % or the noise floor, "
       << "whichever is larger (docs/accuracy.md).\n\n";
    md << "## Noise floor\n\n| measure | noise floor |\n|---|---|\n";
    for (int m = 0; m < kMeasures; ++m)
      md << "| " << kMeasureNames[m] << " | "
         << (m == kMeasures - 1 ? fmt(noise_[m], "%.2e") : fmt(100.0 * noise_[m], "%.3f %%")) << " |\n";
    md << "\nThe scene as given took " << fmt(reference_.wall_seconds, "%.1f") << " s (" << reference_.steps
       << " steps, FIRE " << reference_.fire_steps << (reference_.fire_converged ? "" : ", not converged")
       << ")";
    if (!replicas_.empty()) {
      md << "; its replicas";
      for (const Row& r : replicas_)
        md << (&r == &replicas_.front() ? " " : ", ") << fmt(r.wall_seconds, "%.1f") << " s (FIRE "
           << r.fire_steps << (r.fire_converged ? "" : ", not converged") << ")";
      const bool fire_differs = std::any_of(replicas_.begin(), replicas_.end(), [&](const Row& r) {
        return r.fire_steps != reference_.fire_steps;
      });
      if (fire_differs)
        md << ". The replicas' relaxations took different step counts, and their wall times follow: a "
              "setting's time ratio means something only beyond this spread; compare its steps and FIRE "
              "steps with the replicas'";
    }
    md << ".\n";
    for (const std::string& knob : knob_names()) {
      std::vector<const Row*> rows;
      for (const Row& r : rows_)
        if (r.knob == knob) rows.push_back(&r);
      if (rows.empty()) continue;
      md << "\n## " << knob << "\n\n| setting | wall (s) | time ratio |";
      const bool bed = std::any_of(rows.begin(), rows.end(), [](const Row* r) { return r->has_bed; });
      if (bed) {
        md << " steps | FIRE steps |";
        for (const char* n : kMeasureNames) md << ' ' << n << " |";
      }
      const bool exact =
          std::any_of(rows.begin(), rows.end(), [](const Row* r) { return std::isfinite(r->exact_error); });
      if (exact) md << " exact error |";
      if (knob == "grid") md << " centre sigma_zz (Pa) |";
      md << "\n|---|---|---|";
      if (bed)
        for (int m = 0; m < kMeasures + 2; ++m) md << "---|";
      if (exact) md << "---|";
      if (knob == "grid") md << "---|";
      md << '\n';
      const Row* cheapest = nullptr;
      for (const Row* r : rows) {
        md << "| " << r->label << (r->is_default ? " (default)" : "") << " | " << fmt(r->wall_seconds, "%.2f")
           << " | " << fmt(r->wall_seconds / reference_.wall_seconds, "%.2f") << " |";
        if (bed) {
          md << ' ' << (r->has_bed ? std::to_string(r->steps) : "-") << " | "
             << (r->has_bed ? std::to_string(r->fire_steps) + (r->fire_converged ? "" : " (not converged)")
                            : "-")
             << " |";
          for (int m = 0; m < kMeasures; ++m) md << ' ' << (r->has_bed ? change_text(*r, m) : "-") << " |";
        }
        if (exact) md << ' ' << fmt(r->exact_error, "%.2e") << " |";
        if (knob == "grid") md << ' ' << fmt(r->point_szz, "%.5g") << " |";
        md << '\n';
        if (acceptable(*r) && (!cheapest || r->wall_seconds < cheapest->wall_seconds)) cheapest = r;
      }
      if (knob == "solver tolerance" || knob == "solver iterations") {
        // The reference's counts and timings differ per setting: one line each.
        md << "\nExact reference, per setting:\n\n";
        for (const Row* r : rows)
          if (std::isfinite(r->exact_error)) md << "- " << r->label << ": " << r->exact_name << ".\n";
      } else {
        for (const Row* r : rows)
          if (std::isfinite(r->exact_error)) {
            md << "\nExact reference: " << r->exact_name << ".\n";
            break;
          }
      }
      if (knob == "skin") {
        bool identical = true;
        for (const Row* r : rows)
          for (int m = 0; m < kMeasures; ++m)
            if (std::isfinite(r->change[m]) && r->change[m] != 0.0) identical = false;
        md << "\nThe skin changes which pairs the lists hold, not a force: every result must be the same "
              "bits. "
           << (identical ? "It is." : "**It is not: every skin must give the same bits.**") << '\n';
        if (!identical) code = 1;
      }
      if (knob == "grid") {
        double lo = 1e300, hi = -1e300;
        for (const Row* r : rows)
          if (std::isfinite(r->point_szz)) lo = std::min(lo, r->point_szz), hi = std::max(hi, r->point_szz);
        if (hi >= lo)
          md << "\nThe grid-size effect: sigma_zz at the centre of the bed spreads by "
             << fmt(100.0 * (hi - lo) / std::abs(0.5 * (hi + lo)), "%.1f") << " % across the resolutions.\n";
      }
      md << "\nCheapest setting within the tolerance: "
         << (cheapest ? cheapest->label + " (" +
                            fmt(cheapest->wall_seconds / reference_.wall_seconds, "%.2f") + " of the time)"
                      : std::string("none"))
         << ".\n";
      if (std::filesystem::exists(UPGRAIN_SCRIPT_DIR))
        md << "\n![" << knob << "](pareto_" << slug(knob) << ".png)\n";
    }
    if (!skipped_.empty()) {
      md << "\n## Knobs not run\n\n";
      for (const std::string& s : skipped_) md << "- " << s << "\n";
    }
    dem::io::write_text_atomically(folder_ / "accuracy.md", md.str());
    if (const FigureRun f = run_figure_script("studies/accuracy/plot_accuracy.py", folder_, "plots.log", {});
        f.ran && !f.succeeded)
      std::printf("  accuracy: plots not made (see %s)\n", (folder_ / "plots.log").c_str());
    std::printf("  accuracy: %s, %s\n", (folder_ / "accuracy.md").c_str(),
                (folder_ / "accuracy.csv").c_str());
    return code;
  }

  const SceneInput& in_;
  MPI_Comm comm_;
  fs::path folder_;
  int rank_ = 0, ranks_ = 1;
  std::vector<KnobSetting> settings_;
  std::vector<std::string> skipped_;
  Row reference_;
  std::vector<Row> replicas_, rows_;
  std::vector<double> noise_;
  int total_runs_ = 0, done_runs_ = 0;
  double done_seconds_ = 0.0;
};

}  // namespace

int run_accuracy_study(const SceneInput& in, MPI_Comm comm, const StudyHooks&) {
  AccuracyStudy study(in, comm);  // its own progress lines, one per run
  return study.run();
}

}  // namespace upgrain::coupling
