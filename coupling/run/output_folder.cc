#include "coupling/run/output_folder.h"

#include <unistd.h>

#include <ctime>
#include <optional>
#include <random>
#include <regex>

#include "dem/core/error.h"
#include "dem/files/output_journal.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;
using dem::io::list_paths;

namespace {

// Removes one path of the run (a file, or a folder being written with what it holds) and its
// manifest entry; an Error naming it when it cannot be removed.
void remove_ours(const fs::path& folder, const std::string& rel) {
  std::error_code ec;
  fs::remove_all(folder / rel, ec);
  if (ec) throw Error("cannot remove " + (folder / rel).string() + ": " + ec.message());
  dem::io::note_removed(folder / rel);
}

// Removes a listed folder when it is empty (what it held of the run is gone, and nothing else
// was in it); an Error when it cannot.
void remove_folder_if_empty(const fs::path& folder, const std::string& rel) {
  std::error_code ec;
  if (!fs::is_empty(folder / rel, ec)) return;
  fs::remove(folder / rel, ec);
  if (ec) throw Error("cannot remove the folder " + (folder / rel).string() + ": " + ec.message());
  dem::io::note_removed(folder / rel);
}

long checkpoint_step(const std::string& rel) {
  static const std::regex name(R"(checkpoints/checkpoint_(\d+)\.h5)");
  std::smatch m;
  return std::regex_match(rel, m, name) ? std::stol(m[1]) : -1;
}

// Drops the entries of paths the run wrote after the checkpoint that are no longer there. A path
// is removed before its entry (a kill between the two never leaves a file of the run unlisted:
// docs/output.md, "Manifest"), so a start killed between the two leaves the entry of a path that
// is gone. The audit sees no file for it, so nothing else removes the entry, and the next
// checkpoint would list the path (docs/restart.md, "What a restart does"). Dropped: a file or
// folder the checkpoint does not hold, any checkpoint (a later one is after the checkpoint; the
// run removes older ones itself, Checkpoint/keep), and any path entered as being written. A
// listed file the checkpoint holds stays listed when it is gone: it is missing from the output.
void forget_gone_after(const fs::path& folder, const std::set<std::string>& at_checkpoint) {
  const std::optional<dem::io::OutputManifest> m = dem::io::journal_manifest();
  if (!m) return;
  std::vector<std::string> gone;
  for (const auto& [rel, e] : m->entries) {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(folder / rel, ec))) continue;
    const bool forget = e.kind == dem::io::ManifestEntry::Kind::being_written || checkpoint_step(rel) >= 0 ||
                        at_checkpoint.count(rel) == 0;
    if (forget) gone.push_back(rel);
  }
  for (const std::string& rel : gone) dem::io::note_removed(folder / rel);
}

}  // namespace

bool holds_no_results(const fs::path& folder) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    if (e.path().filename() != dem::io::kBookkeepingFolder || dem::io::has_manifest(folder)) return false;
  return true;
}

std::string why_not_replaceable(const fs::path& folder) {
  if (!dem::io::has_manifest(folder))
    return "holds files but no manifest of a run (" + dem::io::manifest_path(folder).string() +
           "): Output/overwrite removes only files a run listed there; choose an empty or new folder";
  const dem::io::FolderAudit a = audit_folder(folder, dem::io::read_manifest(folder));
  std::string why;
  if (!a.foreign.empty()) why += "holds what the run there did not write (" + list_paths(a.foreign) + ")";
  if (!a.changed.empty())
    why += std::string(why.empty() ? "" : ", and ") + "holds files of the run there that changed since (" +
           list_paths(a.changed) + ")";
  if (why.empty()) return why;
  return why + "; overwrite removes only what the run wrote, as it wrote it: move these out of the folder";
}

void replace_earlier_run(const fs::path& folder) {
  std::error_code ec;
  if (holds_no_results(folder)) return;
  if (const std::string why = why_not_replaceable(folder); !why.empty())
    throw Error("Output/folder = '" + folder.string() + "' " + why);
  // The files first, then the folders they were in (deepest first), then the manifest: a crash
  // on the way leaves a manifest that lists what remains (a listed file that is gone is simply
  // missing).
  const dem::io::FolderAudit a = audit_folder(folder, dem::io::read_manifest(folder));
  for (const std::vector<std::string>* v : {&a.ours, &a.leftovers})
    for (const std::string& rel : *v)
      if (rel != std::string(dem::io::kBookkeepingFolder) + "/") remove_ours(folder, rel);
  for (const std::string& rel : a.folders) remove_folder_if_empty(folder, rel);
  fs::remove(dem::io::manifest_path(folder), ec);
  if (ec) throw Error("cannot remove " + dem::io::manifest_path(folder).string() + ": " + ec.message());
}

std::vector<std::string> remove_outputs_after(const fs::path& folder,
                                              const std::set<std::string>& at_checkpoint, long step) {
  const std::optional<dem::io::OutputManifest> m = dem::io::journal_manifest();
  if (!m) return {};
  const dem::io::FolderAudit a = audit_folder(folder, *m);
  // A file the run was writing when it died goes, unless the checkpoint knew it: a table that was
  // being appended to, an XDMF being rewritten; the resume cuts those back or rewrites them.
  for (const std::string& rel : a.leftovers)
    if (at_checkpoint.count(rel) == 0) remove_ours(folder, rel);
  for (const std::string& rel : a.ours) {
    if (rel.rfind(dem::io::kBookkeepingFolder, 0) == 0) continue;
    const long checkpoint = checkpoint_step(rel);
    const bool later = checkpoint >= 0 ? checkpoint > step : at_checkpoint.count(rel) == 0;
    if (later) remove_ours(folder, rel);
  }
  for (const std::string& rel : a.folders)
    if (at_checkpoint.count(rel) == 0) remove_folder_if_empty(folder, rel);
  forget_gone_after(folder, at_checkpoint);
  std::vector<std::string> notes;
  if (!a.foreign.empty()) notes.push_back("left alone, not written by the run: " + list_paths(a.foreign));
  if (!a.changed.empty())
    notes.push_back("left alone, changed since the run wrote them: " + list_paths(a.changed));
  return notes;
}

Verification verify_output_folder(const fs::path& folder) {
  Verification v;
  if (!dem::io::has_manifest(folder))
    throw Error(folder.string() + " holds no manifest of a run (" + dem::io::manifest_path(folder).string() +
                "): not an output folder of upgrain, or of a version before manifests");
  const dem::io::OutputManifest m = dem::io::read_manifest(folder);
  const dem::io::FolderAudit a = audit_folder(folder, m);
  std::size_t files = 0;
  for (const auto& [path, e] : m.entries) files += e.kind == dem::io::ManifestEntry::Kind::file ? 1 : 0;
  v.lines.push_back(folder.string() + ": run " + m.run_id + ", " + m.status + ", " + std::to_string(files) +
                    " files listed");
  const auto say = [&](const std::vector<std::string>& paths, const std::string& what) {
    if (paths.empty()) return;
    v.lines.push_back("  " + std::to_string(paths.size()) + " " + what + ":");
    for (const std::string& p : paths) v.lines.push_back("    " + p);
  };
  say(a.missing, "missing (listed, not in the folder)");
  say(a.changed, "changed (not the bytes the run wrote)");
  say(a.foreign, "extra (not written by the run)");
  say(a.leftovers, "left half-written (the run stopped while writing them)");
  v.whole = a.missing.empty() && a.changed.empty() && a.foreign.empty() && a.leftovers.empty();
  v.lines.push_back(v.whole ? "  every listed file is present with the bytes the run wrote; nothing else"
                            : "  the folder is not as the run left it");
  return v;
}

dem::io::OutputManifest check_run_identity(const fs::path& folder, const Checkpoint& c) {
  if (!dem::io::has_manifest(folder))
    throw Error(folder.string() + " holds no manifest of a run (" + dem::io::manifest_path(folder).string() +
                "), so a restart cannot tell the run's files from others; it was not written by this version "
                "of upgrain");
  dem::io::OutputManifest m = dem::io::read_manifest(folder);
  const std::string where = (folder / "checkpoints").string();
  if (c.run_id.empty())
    throw Error("checkpoint " + c.file.string() + " names no run, so it is not of the run " + m.run_id +
                " that the folder's manifest names; remove it from " + where);
  if (c.run_id != m.run_id)
    throw Error("checkpoint " + c.file.string() + " is of run " + c.run_id + ", but the folder " +
                folder.string() + " holds run " + m.run_id +
                " (its manifest): a checkpoint of another run was put there; remove it from " + where);
  return m;
}

std::string host_name() {
  char host[256] = "unknown";
  ::gethostname(host, sizeof host - 1);
  return host;
}

std::string utc_now(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char text[64];
  std::strftime(text, sizeof text, format, &utc);
  return text;
}

std::string new_run_id() {
  std::random_device device;
  char random[9];
  std::snprintf(random, sizeof random, "%08x", static_cast<unsigned>(device()));
  return utc_now("%Y%m%dT%H%M%SZ") + "-" + host_name() + "-" + std::to_string(::getpid()) + "-" + random;
}

}  // namespace upgrain::coupling
