#include "dem/files/output_journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <utility>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/files/fnv1a.h"

namespace upgrain::dem::io {

namespace fs = std::filesystem;

namespace {

struct Journal {
  fs::path folder;  // absolute, lexically normal
  OutputManifest manifest;
  // A complete file's digest while it is being appended to: continued over the new bytes.
  std::map<std::string, FileDigest> before_append;
};

std::optional<Journal>& journal() {
  static std::optional<Journal> j;
  return j;
}

// The path relative to the output folder, or empty when it is not under it.
std::string in_folder(const fs::path& path) {
  const Journal& j = *journal();
  std::error_code ec;
  const fs::path abs = fs::absolute(path, ec).lexically_normal();
  const fs::path rel = abs.lexically_relative(j.folder);
  if (rel.empty() || rel == "." || *rel.begin() == "..") return {};
  return rel.generic_string();
}

// The manifest replaces the previous one in one rename. It is not synced: the files it lists
// are (atomic_file.h), and a manifest older than the folder after a power cut lists a file as
// being written or not at all, so the file is kept, never removed by mistake.
void save() {
  const Journal& j = *journal();
  const fs::path file = manifest_path(j.folder);
  fs::path tmp = file;
  tmp += ".tmp." + std::to_string(::getpid());
  const std::string text = j.manifest.to_text();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error("cannot write the output manifest " + file.string() + ": " + std::strerror(errno));
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t put = ::write(fd, text.data() + done, text.size() - done);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) {
      const int e = put < 0 ? errno : ENOSPC;
      ::close(fd);
      ::unlink(tmp.c_str());
      throw Error("cannot write the output manifest " + file.string() + ": " + std::strerror(e));
    }
    done += static_cast<std::size_t>(put);
  }
  if (::close(fd) != 0 || ::rename(tmp.c_str(), file.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    throw Error("cannot write the output manifest " + file.string() + ": " + std::strerror(e));
  }
}

}  // namespace

void open_output_journal(const fs::path& folder, OutputManifest manifest) {
  std::error_code ec;
  fs::create_directories(folder / kBookkeepingFolder, ec);
  if (ec) throw Error("cannot create folder " + (folder / kBookkeepingFolder).string() + ": " + ec.message());
  // A manifest's temporary copy left by a process killed while it saved one.
  for (const fs::directory_entry& e : fs::directory_iterator(folder / kBookkeepingFolder, ec))
    if (e.path().filename().string().rfind("manifest.tmp.", 0) == 0) fs::remove(e.path(), ec);
  journal() = Journal{fs::absolute(folder).lexically_normal(), std::move(manifest), {}};
  try {
    save();
  } catch (...) {
    journal().reset();
    throw;
  }
}

void close_output_journal(const std::string& status) {
  if (!journal()) return;
  journal()->manifest.status = status;
  try {
    save();
  } catch (const std::exception&) {
    // The manifest on disk then says "running": the folder is kept as it is, never lost.
  }
  journal().reset();
}

bool output_journal_open() { return journal().has_value(); }

void note_writing(const fs::path& path) {
  if (!journal()) return;
  const std::string rel = in_folder(path);
  if (rel.empty()) return;
  ManifestEntry& e = journal()->manifest.entries[rel];
  if (e.kind == ManifestEntry::Kind::being_written) return;
  if (e.kind == ManifestEntry::Kind::file) journal()->before_append[rel] = FileDigest{e.size, e.hash};
  e = ManifestEntry{ManifestEntry::Kind::being_written, 0, 0};
  save();
}

void note_written(const fs::path& path) {
  if (!journal()) return;
  const std::string rel = in_folder(path);
  if (rel.empty()) return;
  const FileDigest d = digest_file(path);
  journal()->before_append.erase(rel);
  journal()->manifest.entries[rel] = ManifestEntry{ManifestEntry::Kind::file, d.size, d.hash};
  save();
}

void note_appended(const fs::path& path, const void* data, std::size_t n) {
  if (!journal()) return;
  const std::string rel = in_folder(path);
  if (rel.empty()) return;
  const auto before = journal()->before_append.find(rel);
  if (before == journal()->before_append.end()) {
    note_written(path);  // new, or not complete before: read whole
    return;
  }
  Fnv1a hash(before->second.hash);
  hash.add(data, n);
  journal()->manifest.entries[rel] =
      ManifestEntry{ManifestEntry::Kind::file, before->second.size + n, hash.value()};
  journal()->before_append.erase(before);
  save();
}

void note_folder(const fs::path& folder) {
  if (!journal()) return;
  const std::string rel = in_folder(folder);
  if (rel.empty()) return;
  auto [it, added] =
      journal()->manifest.entries.try_emplace(rel, ManifestEntry{ManifestEntry::Kind::folder, 0, 0});
  if (!added && it->second.kind == ManifestEntry::Kind::folder) return;
  it->second = ManifestEntry{ManifestEntry::Kind::folder, 0, 0};
  save();
}

void note_removed(const fs::path& path) {
  if (!journal()) return;
  const std::string rel = in_folder(path);
  if (rel.empty()) return;
  if (journal()->manifest.entries.erase(rel) > 0) save();
}

void note_pieces_writing(MPI_Comm comm, const fs::path& folder, const std::vector<fs::path>& pieces) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0) {
    try {
      create_folder(folder);
      for (const fs::path& p : pieces) note_writing(p);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  int failed = error.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (failed) throw Error(rank == 0 ? error : "rank 0 could not make " + folder.string() + " for the pieces");
}

void note_pieces_written(MPI_Comm comm, const std::vector<fs::path>& pieces) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    for (const fs::path& p : pieces) note_written(p);
}

std::set<std::string> journal_paths() {
  std::set<std::string> out;
  if (!journal()) return out;
  for (const auto& [path, e] : journal()->manifest.entries)
    if (e.kind != ManifestEntry::Kind::being_written) out.insert(path);
  return out;
}

std::optional<OutputManifest> journal_manifest() {
  if (!journal()) return std::nullopt;
  return journal()->manifest;
}

}  // namespace upgrain::dem::io
