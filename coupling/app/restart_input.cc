#include "coupling/app/restart_input.h"

#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "coupling/input/scene_text.h"
#include "coupling/run/checkpoint.h"
#include "coupling/run/output_folder.h"
#include "coupling/run/resume_point.h"
#include "dem/core/error.h"
#include "dem/io/file_kind.h"
#include "dem/parallel/exchange.h"

namespace upgrain::coupling {

SceneInput restart_input(const std::string& dir, const std::string& file, const StudyUse& use,
                         std::vector<std::string>& notes) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::shared_ptr<Checkpoint> checkpoint;
  std::string scene, newest, error, study;
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
      checkpoint = std::make_shared<Checkpoint>(newest_checkpoint(dir, refused));
      for (const std::string& r : refused) notes.push_back("refused " + r);
      (void)check_run_identity(dir, *checkpoint);  // before its scene is taken
      scene = checkpoint->scene;
      newest = checkpoint->file.string();
      if (checkpoint->study) study = checkpoint->study->study;
      // A study that keeps its own state continues only its own checkpoints, and only it continues
      // them.
      const std::string asked(use.name);
      if (study.empty() ? use.own_state : study != asked)
        throw Error("--restart " + dir + ": " +
                    (study.empty()
                         ? "its checkpoints are of a DEM run, not of --study " + asked +
                               "; continue it without --study " + asked
                         : "it is a run of --study " + study + "; continue it with upgrain --study " + study +
                               " --restart " + dir));
      step = checkpoint->step;
      time = checkpoint->time;
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  dem::throw_if_any(MPI_COMM_WORLD, error);
  MPI_Bcast(&step, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  MPI_Bcast(&time, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (std::string* text : {&scene, &newest, &study}) {
    int length = static_cast<int>(text->size());
    MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
    text->resize(static_cast<std::size_t>(length));
    MPI_Bcast(text->data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  }
  SceneInput in = parse_scene_text(scene, dir + ": the scene of its checkpoint");
  in.use = use;
  const long checkpoint_end = end_step(in.scene);
  if (!file.empty()) {
    // The given file's values for what a restart may change, the checkpoint's for the rest.
    SceneInput given = parse_scene_text(read_scene_bytes(file), file);
    in.scene_folder = std::filesystem::path(file).parent_path().string();
    const std::vector<std::string> differ = differing_parameters(scene, given.output.checkpoint.scene);
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
  if (!study.empty()) {
    // The study's own state: it knows where its loading stands (its steps, not the scene's time).
    if (rank == 0) notes.push_back("resuming from " + newest + " after load step " + std::to_string(step));
  } else {
    // Every rank has the checkpoint's step and the end time: a refusal is every rank's.
    const long end = end_step(in.scene);
    refuse_end_before(file.empty() ? dir : file, in.scene.end_time, end, newest, step, time);
    if (!may_continue_from(step, end, checkpoint_end, in.control.relax_at_end)) {
      if (rank == 0) {
        try {
          notes.push_back("checkpoint " + checkpoint->file.string() + " is at the run's end step, " +
                          std::to_string(end) +
                          ": the end of a run is made from what that step left in memory, which a checkpoint "
                          "does not hold; continuing from the one before");
          std::vector<std::string> refused;
          checkpoint = std::make_shared<Checkpoint>(newest_checkpoint(dir, refused, end));
          for (const std::string& r : refused) notes.push_back("refused " + r);
          (void)check_run_identity(dir, *checkpoint);
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
      std::snprintf(where, sizeof where, "resuming from %s at step %ld (t = %.9g s)",
                    checkpoint->file.c_str(), checkpoint->step, checkpoint->time);
      notes.push_back(where);
    }
  }
  // Later errors name what the user ran, not the checkpoint's copy of the scene.
  in.source = file.empty() ? "upgrain --restart " + dir : file;
  // A calibrated material file: from the given scene file's folder, or the current one.
  apply_material_file(in, file);
  in.output.folder = dir;
  in.restarting = true;
  in.resume = checkpoint;
  validate_scene(in);
  return in;
}

}  // namespace upgrain::coupling
