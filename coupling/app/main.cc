// upgrain: the driver. It parses the command line and the scene file for the study it names
// (coupling/studies/study_table.h), takes the output folder (its lock and manifest), and runs
// the study through its row.
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <set>
#include <string>

#include "coupling/app/quiet_p4est.h"
#include "coupling/app/restart_input.h"
#include "coupling/app/run_printout.h"
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_limits.h"
#include "coupling/run/checkpoint.h"
#include "coupling/run/folder_lock.h"
#include "coupling/run/output_folder.h"
#include "coupling/run/resume_point.h"
#include "coupling/run/scene_run.h"
#include "coupling/run/stop_request.h"
#include "coupling/studies/study_table.h"
#include "dem/core/error.h"
#include "dem/files/output_journal.h"
#include "dem/parallel/exchange.h"
#include "dem/parallel/mpi_start.h"
#include "dem/time_step.h"

namespace {

// upgrain --help: the options, with each study's row (coupling/studies/study_table.cc).
std::string usage() {
  std::string text =
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
      "  --output DIR                  override Output/folder\n";
  // Each study's lines, its name in the option's column and its help beside it.
  for (const upgrain::coupling::Study& study : upgrain::coupling::studies()) {
    std::string option = "  --study " + std::string(study.use.name);
    option.resize(std::max<std::size_t>(option.size() + 1, 32), ' ');
    std::string_view help = study.help;
    for (std::size_t line = 0; !help.empty(); ++line) {
      const std::size_t end = help.find('\n');
      text += (line == 0 ? option : std::string(32, ' ')) + std::string(help.substr(0, end)) + "\n";
      help = end == std::string_view::npos ? std::string_view{} : help.substr(end + 1);
    }
  }
  return text +
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
  std::string file, output_override, restart_dir;
  const coupling::Study* study = &coupling::studies().front();  // without --study
  bool check_only = false;
  // The command line is every rank's: its errors are said once (CollectiveError).
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "-h" || a == "--help") {
      std::cout << usage();
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
      if (k + 1 >= argc)
        throw CollectiveError("--study needs the name of a study (" + coupling::study_names() + ")");
      study = &coupling::study_named(argv[++k]);
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
  // Every rank reads and checks the scene, and they agree on the outcome before rank 0 creates
  // the output folder: a refusal is every rank's, printed once.
  std::string refusal;
  try {
    if (!restart_dir.empty()) {
      in = coupling::restart_input(restart_dir, file, study->use, restart_notes);
    } else {
      in = file.empty() ? coupling::default_scene(study->use) : coupling::read_scene_file(file, study->use);
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
    const std::string grains = dem::has_shapes(in.scene.particles.shapes)
                                   ? "grains (" + dem::shape_nouns(in.scene.particles.shapes) + ")"
                                   : "spheres";
    if (study->use.runs_scene)
      std::printf("upgrain: %s\n  %ld %s, time step %.3g s (safe %.3g s, %s-limited), end time %.3g s\n",
                  in.source.c_str(), in.scene.particles.count, grains.c_str(), in.scene.time_step,
                  ts.safe_step, ts.limiting.c_str(), in.scene.end_time);
    else
      std::printf(
          "upgrain: %s\n  DEM cells of %s, time step %.3g s (safe %.3g s, %s-limited); the scene's particle "
          "count, end time and effects are not used (--study %s prepares its own cells)\n",
          in.source.c_str(), grains.c_str(), in.scene.time_step, ts.safe_step, ts.limiting.c_str(),
          std::string(study->use.name).c_str());
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
    if (study->use.runs_scene) {
      std::printf("  effects (Effects section; auto = derived from the scene):\n");
      for (const dem::EffectChoice& c : in.output.effect_choices)
        std::printf("    %-20s %-3s  %s\n", c.entry.c_str(), c.on ? "on" : "off", c.reason.c_str());
    }
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
    if (!study->use.checkpoints)
      std::printf("  checkpoints: none (--study %s drives its own cells; Checkpoint is not used)\n",
                  std::string(study->use.name).c_str());
    else if (study->use.own_state) {
      // Its state after a load step: no simulated time to schedule by.
      char wall[64] = "when asked to stop";
      if (c.wall_interval > 0.0)
        std::snprintf(wall, sizeof wall, "every %g s of wall clock and when asked to stop", c.wall_interval);
      std::printf("  checkpoints: %s, after a converged load step, the last %d kept%s\n", wall, c.keep,
                  c.interval > 0.0 ? " (Checkpoint/interval, simulated time, is not used)" : "");
    } else if (!every.empty())
      std::printf("  checkpoints: %s, the last %d kept\n", every.c_str(), c.keep);
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
    if (rank == 0) coupling::print_progress(p);
  };
  const auto run_it = [&]() -> int {
    coupling::StudyHooks hooks{progress,
                               [&](const coupling::RunResult& r) { coupling::print_deposition(in, r); }};
    if (const int code = study->run(in, MPI_COMM_WORLD, hooks); code != 0) return code;
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
        std::printf("  continue with: upgrain %s--restart %s\n",
                    study->use.own_state ? ("--study " + std::string(study->use.name) + " ").c_str() : "",
                    in.output.folder.c_str());
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
