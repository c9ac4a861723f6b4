// upgrain: the driver. It only parses the command line and the scene file, then hands
// plain structs to the run of the scene (coupling/run/scene_run.h) or the study.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <new>
#include <set>
#include <sstream>
#include <string>

#include "coupling/accuracy/accuracy_study.h"
#include "coupling/calibration/calibration_study.h"
#include "coupling/dem_run.h"
#include "coupling/quiet_p4est.h"
#include "coupling/run/checkpoint.h"
#include "coupling/run/folder_lock.h"
#include "coupling/run/output_folder.h"
#include "coupling/run/resume_point.h"
#include "coupling/run/scene_run.h"
#include "coupling/run/stop_request.h"
#include "coupling/run/stress_summary.h"
#include "coupling/scene_input.h"
#include "coupling/scene_limits.h"
#include "coupling/scene_text.h"
#include "coupling/strain_report.h"
#include "coupling/study.h"
#include "dem/core/error.h"
#include "dem/files/output_journal.h"
#include "dem/io/file_kind.h"
#include "dem/parallel/exchange.h"
#include "dem/parallel/mpi_start.h"
#include "dem/time_step.h"

namespace {

constexpr const char* kUsage =
    "Usage: upgrain [options] [scene.prm]\n"
    "\n"
    "Runs a DEM deposition scene (spheres poured into an open-top box) and, unless\n"
    "'Study/compare with continuum' is false, the DEM-vs-continuum study: grid stress,\n"
    "the elastic column of the same container (deal.II), comparison tables, plots and a\n"
    "report, all in the output folder. Without a file, runs the built-in default study\n"
    "(about 2,000 spheres on a 3 x 3 x 4 grid, a few minutes). Under mpirun the\n"
    "DEM and the continuum run on every rank (Parallel section).\n"
    "\n"
    "Options:\n"
    "  -h, --help                    this text\n"
    "  --print-parameters            print the complete annotated default parameter file\n"
    "  --print-parameters-markdown   the same as a Markdown table (docs/parameters.md)\n"
    "  --check                       read and validate the scene, print the time-step\n"
    "                                estimate, write nothing\n"
    "  --output DIR                  override Output/folder\n"
    "  --study accuracy              run the accuracy study of the scene (its Accuracy section,\n"
    "                                docs/accuracy.md): every knob's values against wall time,\n"
    "                                into <Output/folder>/accuracy/\n"
    "  --study calibration           deposit the scene's bed and compress it under a servo lid in\n"
    "                                stress steps (its Calibration section, docs/calibration.md):\n"
    "                                the stress-strain path and the equivalent elastic material,\n"
    "                                into <Output/folder>/calibration/\n"
    "  --verify DIR                  check the output folder DIR against its manifest: the files\n"
    "                                missing, changed, extra or left half-written (docs/output.md)\n"
    "  --restart DIR                 continue the run in DIR from its newest valid checkpoint\n"
    "                                (DIR/checkpoints/, docs/restart.md), with the scene it was\n"
    "                                started with; a scene file given as well may change only\n"
    "                                Simulation/end time and maximum steps and the Checkpoint and\n"
    "                                Parallel sections\n"
    "\n"
    "Exit status: 0 done (--verify: the folder is whole), 1 an error (named on one line; --verify:\n"
    "the folder is not as its run left it), 128 + N stopped by signal N\n"
    "(130 SIGINT, 143 SIGTERM, 129 SIGHUP) after writing a checkpoint.\n";

// One line, rewritten in place; a new phase starts a new line. The time left is at the rate of
// the last seconds (coupling/run/progress_clock.h): a bound, not a promise, where the run may
// stop sooner at rest or at its relaxation tolerance.
void print_progress(const upgrain::coupling::Progress& p) {
  using Phase = upgrain::coupling::Progress::Phase;
  static Phase shown = Phase::dynamics;
  if (p.phase != shown) std::printf("\n");
  shown = p.phase;
  const double pct = 100.0 * static_cast<double>(p.step) / static_cast<double>(std::max(p.total_steps, 1L));
  char line[200];
  if (p.phase == Phase::dynamics)
    std::snprintf(line, sizeof line, "  %5.1f %%  step %ld/%ld  %.0f steps/s  ETA %.0f s%s", pct, p.step,
                  p.total_steps, p.steps_per_second, p.eta_seconds, p.may_end_sooner ? " or at rest" : "");
  else
    std::snprintf(line, sizeof line,
                  "  relaxing (FIRE)  step %ld/%ld  residual %.1e, stops at %.0e  ETA <= %.0f s", p.step,
                  p.total_steps, p.residual, p.tolerance, p.eta_seconds);
  // Padded to the previous line's length only: a line longer than the terminal would wrap.
  static int previous = 0;
  const int length = static_cast<int>(std::strlen(line));
  std::printf("\r%-*s", std::max(length, previous), line);
  previous = length;
  std::fflush(stdout);
}

void print_deposition(const upgrain::coupling::SceneInput& in, const upgrain::coupling::RunResult& r) {
  using namespace upgrain;
  std::printf("\n  done: %ld steps, %.3g s simulated in %.1f s (%.3g particle-steps/s)%s\n", r.steps,
              r.simulated_time, r.wall_seconds, r.particle_steps_per_second,
              r.stopped_at_rest ? ", stopped at rest" : "");
  if (!r.history.resumed_at.empty())
    std::printf("  over %zu segments (resumed at step %ld last), this one %.1f s\n",
                r.history.resumed_at.size() + 1, r.history.resumed_at.back(), r.segment_seconds);
  if (r.relaxation)
    std::printf("  relaxed to static equilibrium: %ld FIRE steps, residual force %.2e, torque %.2e%s\n",
                r.relaxation->steps, r.relaxation->max_force_residual, r.relaxation->max_torque_residual,
                r.relaxation->converged ? "" : " (not converged: step limit)");
  if (in.scene.insertion.enabled())
    std::printf("  poured: %ld of %ld grains (Insertion/count)\n", r.inserted, in.scene.insertion.count);
  const long grains = in.scene.particles.count + r.inserted;
  std::printf("  bed: surface %.4f m, solid fraction %.4f, %.2f contacts per particle, %ld outside\n",
              r.bed.surface_height, r.bed.solid_fraction,
              grains > 0
                  ? 2.0 * static_cast<double>(r.diagnostics.particle_contacts) / static_cast<double>(grains)
                  : 0.0,
              r.bed.particles_outside);
  if (std::isfinite(r.kinetic_to_released))
    std::printf("  energy: kinetic/released %.3e, balance error %.3e\n", r.kinetic_to_released,
                r.energy_balance_error);
  else
    std::printf("  energy: no potential energy released (kinetic/released undefined), balance error %.3e\n",
                r.energy_balance_error);
  if (r.load.ranks > 1)
    std::printf(
        "  load over %d ranks: owned particles max/mean %.3f, compute time max/mean %.3f, communication up "
        "to %.1f %% of a rank's step time, %ld rebalances\n",
        r.load.ranks, r.load.owned_imbalance, r.load.compute_imbalance, 100.0 * r.load.communication_share,
        r.load.rebalances);
  const dem::ContactSolverStats& cs = r.diagnostics.contact_solver;
  if (cs.calls > 0)
    std::printf(
        "  ellipsoid contacts: %lld solver calls (%lld warm, %.2f Newton steps per call), %lld proven "
        "apart before the solver, %lld still apart by an earlier proof, %lld fallbacks, %lld uncertified, "
        "%lld "
        "not converged\n",
        static_cast<long long>(cs.calls), static_cast<long long>(cs.warm_starts),
        static_cast<double>(cs.newton_iterations) / static_cast<double>(cs.calls),
        static_cast<long long>(cs.proven_apart), static_cast<long long>(cs.still_apart),
        static_cast<long long>(cs.fallbacks), static_cast<long long>(cs.uncertified),
        static_cast<long long>(cs.failures));
  if (r.final_stress) {
    const dem::GridStress& g = *r.final_stress;
    const dem::RegularGrid& grid = r.final_grid;
    std::printf("  grid stress (%d x %d x %d cells up to z = %.4f m), final state:\n", grid.n[0], grid.n[1],
                grid.n[2], grid.hi.z());
    for (dem::StressFormula f : in.output.grid_stress.formulas) {
      const coupling::StressSummary s = coupling::summarise_stress(g, grid, f);
      char rai[96];
      if (s.rated_cells == 0)
        std::snprintf(rai, sizeof rai, "no cell with measurable stress");
      else if (std::isinf(s.max_rai))
        std::snprintf(rai, sizeof rai, "max RAI unbounded (a cell with skew stress only)");
      else
        std::snprintf(rai, sizeof rai, "max RAI %.3g %%", 100.0 * s.max_rai);
      std::printf("    %-18s %s", std::string(dem::name_of(f)).c_str(), rai);
      if (s.negligible_cells > 0)
        std::printf(" (%d cell%s with grains but negligible stress left out)", s.negligible_cells,
                    s.negligible_cells > 1 ? "s" : "");
      std::printf(", mean sigma_zz of the bottom layer %.6g Pa\n", s.floor_szz);
    }
  }
  std::printf("  results: %s/{summary.json,time_series.csv,particles.xdmf,snapshots/%s%s}\n",
              in.output.folder.c_str(),
              r.final_stress ? ",grid_stress.csv,grid_stress.xdmf,grid_stress/" : "",
              r.final_strain ? ",grid_strain.csv,grid_strain.xdmf,grid_strain/" : "");
  std::fflush(stdout);
}

// The scene of a run to continue (upgrain --restart DIR [scene.prm]): rank 0 reads the newest
// valid checkpoint of DIR, every rank the scene it stores; a scene file given as well may change
// only what a restart may (coupling::differing_parameters), and may not end before the
// checkpoint (coupling/run/resume_point.h). `notes` receives what the log should say (refused
// checkpoints, where the run resumes), on rank 0.
upgrain::coupling::SceneInput restart_input(const std::string& dir, const std::string& file,
                                            upgrain::coupling::Command command,
                                            std::vector<std::string>& notes) {
  using namespace upgrain;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::shared_ptr<coupling::Checkpoint> checkpoint;
  std::string scene, newest, error;
  long step = 0;
  double time = 0.0;
  if (rank == 0) {
    try {
      // Named as what it is: a file, a FIFO or a symbolic link loop is not a folder without
      // checkpoints.
      if (const dem::io::PathKind k = dem::io::path_kind(dir); !k.folder())
        throw Error("--restart " + dir + ": " +
                    (k.exists ? "is " + k.description + ", not the output folder of a run"
                              : k.description + "; give the output folder of the run to continue"));
      std::vector<std::string> refused;
      checkpoint = std::make_shared<coupling::Checkpoint>(coupling::newest_checkpoint(dir, refused));
      for (const std::string& r : refused) notes.push_back("refused " + r);
      (void)coupling::check_run_identity(dir, *checkpoint);  // before its scene is taken
      scene = checkpoint->scene;
      newest = checkpoint->file.string();
      step = checkpoint->step;
      time = checkpoint->time;
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  dem::throw_if_any(MPI_COMM_WORLD, error);
  MPI_Bcast(&step, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  MPI_Bcast(&time, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (std::string* text : {&scene, &newest}) {
    int length = static_cast<int>(text->size());
    MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
    text->resize(static_cast<std::size_t>(length));
    MPI_Bcast(text->data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  }
  coupling::SceneInput in = coupling::parse_scene_text(scene, dir + ": the scene of its checkpoint");
  in.command = command;
  const long checkpoint_end = coupling::end_step(in.scene);
  if (!file.empty()) {
    // The given file's values for what a restart may change, the checkpoint's for the rest.
    coupling::SceneInput given = coupling::parse_scene_text(coupling::read_scene_bytes(file), file);
    in.scene_folder = std::filesystem::path(file).parent_path().string();
    const std::vector<std::string> differ =
        coupling::differing_parameters(scene, given.output.checkpoint.scene);
    if (!differ.empty()) {
      std::string m = file + " is not the scene of the run in " + dir + "; it differs in";
      for (const std::string& d : differ) m += "\n  " + d;
      throw Error(m +
                  "\n(a restart may change only Simulation/end time and maximum steps and the Checkpoint "
                  "and Parallel sections but the summation)");
    }
    in.scene.end_time = given.scene.end_time;
    in.maximum_steps = given.maximum_steps;
    in.output.checkpoint = given.output.checkpoint;  // with the given file's text: its end time
    in.parallel = given.parallel;
  }
  // Every rank has the checkpoint's step and the end time: a refusal is every rank's.
  const long end = coupling::end_step(in.scene);
  coupling::refuse_end_before(file.empty() ? dir : file, in.scene.end_time, end, newest, step, time);
  if (!coupling::may_continue_from(step, end, checkpoint_end, in.control.relax_at_end)) {
    if (rank == 0) {
      try {
        notes.push_back("checkpoint " + checkpoint->file.string() + " is at the run's end step, " +
                        std::to_string(end) +
                        ": the end of a run is made from what that step left in memory, which a checkpoint "
                        "does not hold; continuing from the one before");
        std::vector<std::string> refused;
        checkpoint = std::make_shared<coupling::Checkpoint>(coupling::newest_checkpoint(dir, refused, end));
        for (const std::string& r : refused) notes.push_back("refused " + r);
        (void)coupling::check_run_identity(dir, *checkpoint);
      } catch (const std::exception& e) {
        error = "cannot continue the run in " + dir + " to its end step " + std::to_string(end) +
                ": its newest checkpoint, " + newest +
                ", is at that step, and a restart takes at least one step (the end of a run is made from "
                "what its last step left in memory, which a checkpoint does not hold); " +
                e.what() + ". Give a later end time, or run the scene again";
      }
    }
    dem::throw_if_any(MPI_COMM_WORLD, error);
  }
  if (rank == 0) {
    char where[256];
    std::snprintf(where, sizeof where, "resuming from %s at step %ld (t = %.9g s)", checkpoint->file.c_str(),
                  checkpoint->step, checkpoint->time);
    notes.push_back(where);
  }
  // Later errors name what the user ran, not the checkpoint's copy of the scene.
  in.source = file.empty() ? "upgrain --restart " + dir : file;
  // A calibrated material file: from the given scene file's folder, or the current one.
  coupling::apply_material_file(in, file);
  in.output.folder = dir;
  in.restarting = true;
  in.resume = checkpoint;
  coupling::validate_scene(in);
  return in;
}

// upgrain --verify DIR (rank 0 prints): 0 when the folder is as its run left it.
int verify(const std::string& dir) {
  using namespace upgrain;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int whole = 0;
  std::string error;
  if (rank == 0) {
    try {
      const coupling::Verification v = coupling::verify_output_folder(dir);
      for (const std::string& line : v.lines) std::printf("%s\n", line.c_str());
      whole = v.whole ? 1 : 0;
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  dem::throw_if_any(MPI_COMM_WORLD, error);
  MPI_Bcast(&whole, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return whole ? 0 : 1;
}

// The output journal of a run (rank 0; docs/output.md, "Manifest"): a new run's manifest, or the
// manifest of the run a restart continues, after checking that the checkpoint is that run's.
void open_journal(const upgrain::coupling::SceneInput& in) {
  using namespace upgrain;
  const std::filesystem::path& folder = in.output.folder;
  if (!in.restarting) {
    dem::io::OutputManifest m;
    m.run_id = coupling::new_run_id();
    m.scene_hash = coupling::scene_hash(in.output.checkpoint.scene);
    dem::io::open_output_journal(folder, std::move(m));
    return;
  }
  dem::io::OutputManifest m = coupling::check_run_identity(folder, *in.resume);
  m.status = "running";
  dem::io::open_output_journal(folder, std::move(m));
}

// The journal's final status on every way out of a run. A run that failed before it wrote
// anything leaves nothing: its bookkeeping goes, and the folder too when the run made it.
struct JournalClose {
  std::filesystem::path folder;
  bool made_folder = false;
  std::string status = "failed";
  ~JournalClose() {
    namespace io = upgrain::dem::io;
    const bool wrote = io::output_journal_open() && !io::journal_paths().empty();
    const bool open = io::output_journal_open();
    io::close_output_journal(status);
    if (!open || wrote || status != "failed") return;
    std::error_code ec;
    std::filesystem::remove_all(folder / io::kBookkeepingFolder, ec);
    if (made_folder && std::filesystem::is_empty(folder, ec)) std::filesystem::remove(folder, ec);
  }
};

int run(int argc, char** argv) {
  using namespace upgrain;
  std::string file, output_override, restart_dir, study;
  bool check_only = false;
  // The command line is every rank's: its errors are said once (CollectiveError).
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (a == "--print-parameters") {
      coupling::print_default_parameters(std::cout);
      return 0;
    } else if (a == "--print-parameters-markdown") {
      coupling::print_parameters_markdown(std::cout);
      return 0;
    } else if (a == "--check") {
      check_only = true;
    } else if (a == "--study") {
      if (k + 1 >= argc) throw Error("--study needs the name of a study (accuracy, calibration)");
      study = argv[++k];
      if (study != "accuracy" && study != "calibration")
        throw Error("--study: unknown study '" + study + "' (known: accuracy, calibration)");
    } else if (a == "--verify") {
      if (k + 1 >= argc) throw CollectiveError("--verify needs the output folder of a run");
      return verify(argv[++k]);
    } else if (a == "--restart") {
      if (k + 1 >= argc) throw CollectiveError("--restart needs the output folder of the run");
      restart_dir = argv[++k];
    } else if (a == "--output") {
      if (k + 1 >= argc || argv[k + 1][0] == '\0') throw CollectiveError("--output needs a folder name");
      output_override = argv[++k];
    } else if (!a.empty() && a[0] == '-') {
      throw CollectiveError("unknown option '" + a + "' (see upgrain --help)");
    } else if (file.empty()) {
      file = a;
    } else {
      throw CollectiveError("more than one scene file given ('" + file + "', '" + a + "')");
    }
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  coupling::SceneInput in;
  std::vector<std::string> restart_notes;
  if (!restart_dir.empty() && !output_override.empty())
    throw CollectiveError("--restart continues in its own folder: leave out --output");
  const coupling::Command command = study == "accuracy"      ? coupling::Command::accuracy_study
                                    : study == "calibration" ? coupling::Command::calibration_study
                                                             : coupling::Command::run;
  // Every rank reads and checks the scene, and they agree on the outcome before rank 0 creates
  // the output folder: a refusal is every rank's, printed once.
  std::string refusal;
  try {
    if (!restart_dir.empty()) {
      in = restart_input(restart_dir, file, command, restart_notes);
    } else {
      in = file.empty() ? coupling::default_scene(command) : coupling::read_scene_file(file, command);
      if (!output_override.empty()) in.output.folder = output_override;
      in.output.checkpoint.source = in.source;  // a restarted run's report names it
    }
  } catch (const std::exception& e) {
    refusal = e.what();
  }
  dem::throw_if_any(MPI_COMM_WORLD, refusal);
  // The folder the command line chose (--output, --restart) or the scene's: for a run it must be
  // free (docs/output.md); --check only says what a run would meet there.
  std::string folder_note;
  try {
    coupling::check_output_folder(in, in.source + ": ");
  } catch (const std::exception& e) {
    (check_only ? folder_note : refusal) = e.what();
  }
  dem::throw_if_any(MPI_COMM_WORLD, refusal);
  const dem::TimeStepEstimate ts = dem::estimate_time_step(in.scene);
  if (rank == 0) {
    std::printf("upgrain: %s\n  %ld %s, time step %.3g s (safe %.3g s, %s-limited), end time %.3g s\n",
                in.source.c_str(), in.scene.particles.count,
                dem::has_ellipsoids(in.scene.particles.shapes) ? "grains (ellipsoids)" : "spheres",
                in.scene.time_step, ts.safe_step, ts.limiting.c_str(), in.scene.end_time);
    if (coupling::compares_with_continuum(in))
      std::printf(
          "  study: DEM deposition -> grid stress -> continuum column (Q%u) -> comparison and report\n",
          in.study.continuum.degree);
    if (const coupling::ContinuumOptions& c = in.study.continuum; coupling::compares_with_continuum(in)) {
      if (c.calibrate_in_study)
        std::printf(
            "  continuum material: measured on this bed after the DEM run (Continuum/material from = %s): "
            "the "
            "oedometric and friction-angle tests of docs/calibration.md, written to calibration/\n",
            c.material_from_entry());
      else if (!c.calibration_skipped.empty())
        std::printf("  continuum material: the Continuum entries (Continuum/material from = auto): %s\n",
                    c.calibration_skipped.c_str());
    }
    if (const coupling::ContinuumOptions& c = in.study.continuum;
        !c.material_file.empty() && coupling::uses_continuum_material(in))
      std::printf(
          "  continuum material: E %.9g Pa (%s), nu %.9g (%s), friction angle %.9g deg (%s), dilatancy angle "
          "%.9g deg (%s)\n",
          c.youngs_modulus, c.source_of("youngs modulus").c_str(), c.poisson_ratio,
          c.source_of("poisson ratio").c_str(), c.friction_angle_deg, c.source_of("friction angle").c_str(),
          c.dilatancy_angle_deg, c.source_of("dilatancy angle").c_str());
    std::printf("  effects (Effects section; auto = derived from the scene):\n");
    for (const dem::EffectChoice& c : in.output.effect_choices)
      std::printf("    %-20s %-3s  %s\n", c.entry.c_str(), c.on ? "on" : "off", c.reason.c_str());
    std::printf("  %d MPI rank%s, %s summation (Parallel/summation)\n", ranks, ranks > 1 ? "s" : "",
                dem::to_string(in.parallel.summation).c_str());
    if (!in.packing_note.empty()) std::printf("  %s\n", in.packing_note.c_str());
    for (const std::string& w : in.warnings) std::printf("  warning: %s\n", w.c_str());
    if (in.parallel.legacy_engine != "auto")
      std::printf(
          "  warning: Parallel/DEM engine = %s is ignored: one engine runs the DEM on every rank count "
          "(docs/parallel.md); remove the entry\n",
          in.parallel.legacy_engine.c_str());
  }
  if (check_only) {
    if (rank == 0) {
      if (!folder_note.empty())
        std::printf("  note: a run of it would be refused here: %s\n", folder_note.c_str());
      std::printf("  scene is valid; nothing written (--check)\n");
    }
    return 0;
  }
  if (rank == 0) {
    std::printf("  output folder: %s\n", in.output.folder.c_str());
    for (const std::string& note : restart_notes) std::printf("  %s\n", note.c_str());
    // Only the schedules that are on (Checkpoint/interval, wall interval: 0 = off).
    const coupling::CheckpointOptions& c = in.output.checkpoint;
    std::string every;
    char part[64];
    if (c.interval > 0.0) {
      std::snprintf(part, sizeof part, "every %g s simulated", c.interval);
      every = part;
    }
    if (c.wall_interval > 0.0) {
      std::snprintf(part, sizeof part, "every %g s of wall clock", c.wall_interval);
      every += (every.empty() ? "" : ", ") + std::string(part);
    }
    if (!every.empty()) std::printf("  checkpoints: %s, the last %d kept\n", every.c_str(), c.keep);
  }
  std::fflush(stdout);  // the preamble reaches a log file before a run that may be killed
  // The folder is this run's while it lives (docs/output.md, "Lock"); with overwrite the earlier
  // run's files go before the first new one is written; then every file written is entered in
  // the folder's manifest.
  const coupling::FolderLock lock(in.output.folder, MPI_COMM_WORLD);
  if (in.overwrite && !in.restarting)
    dem::run_on_root(MPI_COMM_WORLD, [&] { coupling::replace_earlier_run(in.output.folder); });
  JournalClose journal{in.output.folder, lock.made_folder()};
  dem::run_on_root(MPI_COMM_WORLD, [&] {
    open_journal(in);
    // A restart removes what the run wrote after its checkpoint, and nothing else (docs/restart.md).
    if (in.restarting) {
      const std::set<std::string> listed(in.resume->outputs.begin(), in.resume->outputs.end());
      for (const std::string& note :
           coupling::remove_outputs_after(in.output.folder, listed, in.resume->step))
        std::printf("  %s\n", note.c_str());
    }
  });
  coupling::install_stop_handlers();
  auto progress = [rank](const coupling::Progress& p) {
    if (rank == 0) print_progress(p);
  };
  const auto run_it = [&]() -> int {
    if (study == "accuracy") return coupling::run_accuracy_study(in, MPI_COMM_WORLD);
    if (study == "calibration") return coupling::run_calibration_study(in, MPI_COMM_WORLD, progress);
    if (in.study.compare_with_continuum) {
      if (const int code = coupling::run_study(
              in, MPI_COMM_WORLD, progress, [&](const coupling::RunResult& r) { print_deposition(in, r); });
          code != 0)
        return code;
    } else {
      const coupling::RunResult r = coupling::run_dem(in, MPI_COMM_WORLD, progress);
      if (rank == 0) {
        print_deposition(in, r);
        if (r.final_strain) {  // the strain on the mesh; report.md with the strain section and plots
          (void)coupling::write_strain_mesh(in.output.folder);
          coupling::write_run_report(in.output.folder, in, r, coupling::plot_strain(in.output.folder));
          std::printf("  report: %s\n", (in.output.folder / "report.md").c_str());
        }
      }
    }
    // A stop request after the last step: the end of the run, seconds of writing (or a study's
    // continua), was finished first; it is not ignored either (docs/restart.md).
    if (const int signal = coupling::stop_signal_received(MPI_COMM_WORLD); signal != 0) {
      if (rank == 0) {
        std::printf(
            "\n  stopped by signal %d (%s) after the last step, while the run wrote its results: they were "
            "finished first, and the output in %s is complete (nothing to continue)\n",
            signal, strsignal(signal), in.output.folder.c_str());
        std::fflush(stdout);
      }
      return 128 + signal;
    }
    return 0;
  };
  try {
    const int code = run_it();
    journal.status = code == 0 ? "finished" : code > 128 ? "stopped" : "failed";
    return code;
  } catch (const coupling::RunStopped& stopped) {
    journal.status = "stopped";
    if (rank == 0) {
      std::printf("\n  %s\n", stopped.what());
      if (!stopped.checkpoint().empty())
        std::printf("  continue with: upgrain --restart %s\n", in.output.folder.c_str());
      std::fflush(stdout);
    }
    return 128 + stopped.signal();
  } catch (const CollectiveError& e) {
    throw CollectiveError(in.source + ": " + e.what());
  } catch (const Error& e) {
    throw Error(in.source + ": " + e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  upgrain::dem::prefer_isolated_singleton();
  // Line-buffered even into a file: a batch log of a run killed later keeps every finished line
  // (where a restart resumed, the effects, the stages done).
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  MPI_Init(&argc, &argv);
  upgrain::coupling::quiet_p4est();
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = 0;
  try {
    code = run(argc, argv);
  } catch (const upgrain::CollectiveError& e) {
    // Every rank has it: said once.
    if (rank == 0) {
      std::fflush(stdout);
      std::fprintf(stderr, "\nupgrain: error: %s\n", e.what());
    }
    code = 1;
  } catch (const std::exception& e) {
    // This rank's alone: the others may be waiting for it in a message, so the run is ended
    // (MPI_Abort) rather than left to hang. An allocation that no stage named
    // (dem/core/out_of_memory.h names the big ones) is still said as what it is.
    const std::string what = dynamic_cast<const std::bad_alloc*>(&e) != nullptr
                                 ? "out of memory (std::bad_alloc): the run needs more memory than this "
                                   "process may use (its limits: docs/input.md, \"Memory\")"
                                 : e.what();
    std::fflush(stdout);
    if (ranks > 1) {
      std::fprintf(stderr, "\nupgrain: error on rank %d of %d: %s\n", rank, ranks, what.c_str());
      std::fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    std::fprintf(stderr, "\nupgrain: error: %s\n", what.c_str());
    code = 1;
  }
  MPI_Finalize();
  return code;
}
