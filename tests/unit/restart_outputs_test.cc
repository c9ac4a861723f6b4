// A restart's clean-up of what the run wrote after its checkpoint (coupling/run/output_folder.h,
// remove_outputs_after; docs/restart.md, "What a restart does"; docs/output.md, "Manifest"),
// after a start that was killed at each moment of the same clean-up: the next checkpoint lists
// exactly what the uninterrupted run had written, and nothing the user wrote is removed.
//
// A clean-up removes a path, then its manifest entry. A kill between the two leaves the entry of
// a path that is gone; every such state is made here in turn (no timing involved): the restart
// after it must drop that entry, or the next checkpoint's `outputs` lists the path (a strain
// mesh of the run's end, `end_to_end.restart_after_kill`).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "coupling/run/output_folder.h"
#include "dem/files/atomic_file.h"
#include "dem/files/output_journal.h"
#include "dem/files/output_manifest.h"

namespace fs = std::filesystem;
using namespace upgrain::dem::io;

namespace {

constexpr long kCheckpointStep = 58;

fs::path fresh_folder(const std::string& name) {
  const fs::path f =
      fs::temp_directory_path() / ("upgrain_restart_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(f);
  fs::create_directories(f);
  return f;
}

std::string checkpoint_name(long step) {
  char name[64];
  std::snprintf(name, sizeof name, "checkpoints/checkpoint_%09ld.h5", step);
  return name;
}

// What a checkpoint lists (coupling/run/checkpoint.cc): the journal's paths but the checkpoints.
std::set<std::string> checkpoint_list() {
  std::set<std::string> out;
  for (const std::string& p : journal_paths())
    if (p.rfind("checkpoints/", 0) != 0) out.insert(p);
  return out;
}

// The run from its start to the checkpoint at kCheckpointStep; returns that checkpoint's list.
std::set<std::string> run_to_checkpoint(const fs::path& folder) {
  OutputManifest m;
  m.run_id = "test-run";
  m.scene_hash = "0123456789abcdef";
  open_output_journal(folder, m);
  create_folder(folder / "snapshots");
  write_text_atomically(folder / "snapshots" / "particles_000000050.h5", "snapshot 50");
  write_text_atomically(folder / "time_series.csv", "# t\n0\n");
  create_folder(folder / "checkpoints");
  write_text_atomically(folder / checkpoint_name(56), "checkpoint 56");
  const std::set<std::string> listed = checkpoint_list();
  write_text_atomically(folder / checkpoint_name(kCheckpointStep), "checkpoint 58");
  return listed;
}

// The run from the checkpoint to its end: a snapshot, the checkpoint of the end step (whose list
// is returned), then the end of the run (the strain on the mesh, the report).
std::set<std::string> run_to_end(const fs::path& folder) {
  write_text_atomically(folder / "snapshots" / "particles_000000060.h5", "snapshot 60");
  const std::set<std::string> listed = checkpoint_list();
  write_text_atomically(folder / checkpoint_name(60), "checkpoint 60");
  create_folder(folder / "strain_mesh");
  write_text_atomically(folder / "strain_mesh" / "strain_000000060.0.vtu", "mesh piece");
  write_text_atomically(folder / "strain_mesh" / "strain.pvd", "collection");
  write_text_atomically(folder / "report.md", "report");
  return listed;
}

// A restart (rank 0 of main.cc): the journal opened on the folder's manifest, then the clean-up.
void restart(const fs::path& folder, const std::set<std::string>& at_checkpoint) {
  OutputManifest m = read_manifest(folder);
  m.status = "running";
  open_output_journal(folder, m);
  (void)upgrain::coupling::remove_outputs_after(folder, at_checkpoint, kCheckpointStep);
}

// A start killed: nothing more is saved (the manifest on disk is the last one saved).
void kill() { close_output_journal("running"); }

}  // namespace

// The state a kill leaves at every moment of a restart's clean-up: after the removal of the
// k-th path written after the checkpoint and before the manifest's save without it. The next
// restart's clean-up and its run to the end list at the end step's checkpoint exactly what the
// uninterrupted run listed there; the folder then holds the uninterrupted run's paths, and the
// user's file.
TEST(RestartOutputs, KillAtEveryMomentOfTheCleanUpLeavesTheNextCheckpointsListExact) {
  // The uninterrupted run.
  const fs::path whole = fresh_folder("whole");
  (void)run_to_checkpoint(whole);
  const std::set<std::string> whole_at_end = run_to_end(whole);
  const std::set<std::string> whole_paths = journal_paths();
  close_output_journal("finished");
  ASSERT_EQ(whole_at_end.count("strain_mesh/strain.pvd"), 0u);

  // What the clean-up removes, in its order (remove_outputs_after: the listed files by name,
  // then the folders).
  const std::vector<std::string> after{checkpoint_name(60),
                                       "report.md",
                                       "snapshots/particles_000000060.h5",
                                       "strain_mesh/strain.pvd",
                                       "strain_mesh/strain_000000060.0.vtu",
                                       "strain_mesh"};
  for (std::size_t k = 0; k <= after.size(); ++k) {
    for (const bool entry_saved : {false, true}) {
      SCOPED_TRACE("killed after removing " + std::to_string(k) + " paths, the last one's entry " +
                   (entry_saved ? "saved" : "not saved"));
      const fs::path folder = fresh_folder("broken");
      // Start 1 reaches the end and is killed; the user puts a file of theirs in the folder.
      const std::set<std::string> at_checkpoint = run_to_checkpoint(folder);
      (void)run_to_end(folder);
      kill();
      std::ofstream(folder / "notes.txt") << "the user's";
      // Start 2 resumes at the checkpoint and is killed in its clean-up.
      OutputManifest m = read_manifest(folder);
      open_output_journal(folder, m);
      for (std::size_t i = 0; i < k; ++i) {
        fs::remove_all(folder / after[i]);
        if (i + 1 < k || entry_saved) note_removed(folder / after[i]);
      }
      kill();
      // Start 3 resumes at the checkpoint and runs to the end.
      restart(folder, at_checkpoint);
      EXPECT_EQ(checkpoint_list(), at_checkpoint);
      for (const std::string& p : after) EXPECT_FALSE(fs::exists(fs::symlink_status(folder / p))) << p;
      const std::set<std::string> at_end = run_to_end(folder);
      EXPECT_EQ(at_end, whole_at_end);
      EXPECT_EQ(journal_paths(), whole_paths);
      close_output_journal("finished");
      const FolderAudit a = audit_folder(folder, read_manifest(folder));
      EXPECT_TRUE(a.missing.empty()) << list_paths(a.missing);
      EXPECT_TRUE(a.leftovers.empty()) << list_paths(a.leftovers);
      EXPECT_TRUE(a.changed.empty()) << list_paths(a.changed);
      EXPECT_EQ(a.foreign, std::vector<std::string>{"notes.txt"});
      std::ifstream notes(folder / "notes.txt");
      EXPECT_EQ(std::string(std::istreambuf_iterator<char>(notes), {}), "the user's");
      fs::remove_all(folder);
    }
  }
  fs::remove_all(whole);
}

// An entry of a path being written that is gone (a staging folder removed by a start killed
// before its manifest's save) is dropped; a file the checkpoint lists that is gone stays listed:
// it is missing from the run's output, and `upgrain --verify` says so.
TEST(RestartOutputs, GoneBeingWrittenIsDroppedAndGoneListedFileStaysMissing) {
  const fs::path folder = fresh_folder("gone");
  const std::set<std::string> at_checkpoint = run_to_checkpoint(folder);
  create_folder(folder / "strain_mesh");
  note_writing(folder / "strain_mesh" / ".strain_000000060.tmp.4242");
  kill();
  fs::remove(folder / "time_series.csv");  // the user's doing
  restart(folder, at_checkpoint);
  const OutputManifest m = *journal_manifest();
  EXPECT_EQ(m.entries.count("strain_mesh/.strain_000000060.tmp.4242"), 0u);
  EXPECT_EQ(m.entries.count("strain_mesh"), 0u);
  EXPECT_EQ(m.entries.count("time_series.csv"), 1u);
  EXPECT_EQ(checkpoint_list(), at_checkpoint);
  close_output_journal("stopped");
  EXPECT_EQ(audit_folder(folder, read_manifest(folder)).missing, std::vector<std::string>{"time_series.csv"});
  fs::remove_all(folder);
}
