#pragma once
// A run's output folder and what may be done to it (docs/output.md, "Manifest", "Overwrite";
// docs/restart.md): every decision to remove a file rests on the folder's manifest
// (dem/files/output_manifest.h), so nothing the run did not write is ever removed.
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "coupling/run/checkpoint.h"
#include "dem/files/output_manifest.h"

namespace upgrain::coupling {

// Whether `folder` holds no results: it is missing or empty, or holds nothing but a lock
// (a run that holds it, or held it and wrote nothing).
bool holds_no_results(const std::filesystem::path& folder);

// Why Output/overwrite may not replace `folder`: it has no manifest, or holds files the run did
// not write or that changed since (named). Empty when it may. Reads every listed file.
std::string why_not_replaceable(const std::filesystem::path& folder);

// Removes the earlier run of `folder`: every file and folder its manifest lists, the files it
// was writing, and their temporary files; then its manifest. The folder itself and its lock
// stay. Does nothing when the folder is missing or empty; throws upgrain::Error naming the folder
// and the paths when it holds anything else (nothing is then removed).
void replace_earlier_run(const std::filesystem::path& folder);

// A restart's clean-up (rank 0, with the output journal open on the folder): what the run wrote
// after the checkpoint is removed. That is each listed file and folder that `at_checkpoint` (the
// checkpoint's list) does not hold, the files the run was writing, their temporary files, and the
// checkpoints after `step`; then the entries of such paths that are gone (a start killed during
// its own clean-up, between a removal and the manifest's save, left them: docs/restart.md).
// Files the run did not write are left, and named in the result.
std::vector<std::string> remove_outputs_after(const std::filesystem::path& folder,
                                              const std::set<std::string>& at_checkpoint, long step);

// `upgrain --verify`: the folder against its manifest, as lines for the user, and whether it
// is whole (nothing missing, changed, extra or left half-written).
struct Verification {
  bool whole = false;
  std::vector<std::string> lines;
};
Verification verify_output_folder(const std::filesystem::path& folder);

// The manifest of `folder`, once `checkpoint` is known to be of its run (docs/restart.md): an
// upgrain::Error naming both runs when it is another run's (a checkpoint copied there), or names
// none, or the folder has no manifest.
dem::io::OutputManifest check_run_identity(const std::filesystem::path& folder, const Checkpoint& checkpoint);

// A new run's identity: the UTC time, the host, the process and a random part.
std::string new_run_id();

// This machine's host name, and the time now in UTC by strftime's `format`: what names a run and
// the holder of a folder's lock.
std::string host_name();
std::string utc_now(const char* format);

}  // namespace upgrain::coupling
