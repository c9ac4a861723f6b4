#pragma once
// The manifest of a run's output folder (docs/output.md, "Manifest"): every file and folder the
// run wrote, with each file's size and checksum, and the run's identity. Overwrite, a restart's
// clean-up and `upgrain --verify` decide from it, and from it alone, which files are the run's:
// a file the manifest does not list, or lists with other bytes, is never removed.
//
// The file, <folder>/.upgrain/manifest, is text, one entry per line:
//   F <size> <checksum> <path>   a file, as the run left it (64-bit FNV-1a, dem/files/fnv1a.h)
//   W - - <path>                 a file or folder being written when the manifest was saved
//   D - - <path>                 a folder the run made
// with paths relative to the output folder and '/' between their parts.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace upgrain::dem::io {

// The folder of the run's own bookkeeping (its manifest and lock), inside the output folder.
inline constexpr const char* kBookkeepingFolder = ".upgrain";

struct ManifestEntry {
  enum class Kind : char { file = 'F', being_written = 'W', folder = 'D' };
  Kind kind = Kind::file;
  std::uint64_t size = 0;  // a file's
  std::uint64_t hash = 0;  // a file's checksum
};

struct OutputManifest {
  std::string run_id;      // made when the run starts; its checkpoints carry it too
  std::string scene_hash;  // the hash of the scene's parameter text
  // running, stopped (by a signal, after a checkpoint), failed or finished
  std::string status = "running";
  std::map<std::string, ManifestEntry> entries;  // by path relative to the output folder

  [[nodiscard]] std::string to_text() const;
  // Throws upgrain::Error naming `file` and the line when the text is not a manifest.
  static OutputManifest parse(const std::string& text, const std::string& file);
};

// <folder>/.upgrain/manifest
std::filesystem::path manifest_path(const std::filesystem::path& folder);

// Reads a folder's manifest; an Error naming the file when it is missing or malformed.
OutputManifest read_manifest(const std::filesystem::path& folder);

// Whether `folder` has a manifest file.
bool has_manifest(const std::filesystem::path& folder);

// A file's size and checksum, read from disk.
struct FileDigest {
  std::uint64_t size = 0;
  std::uint64_t hash = 0;
};
FileDigest digest_file(const std::filesystem::path& file);

// What a folder holds against its manifest (paths relative to the folder, sorted).
struct FolderAudit {
  std::vector<std::string> ours;       // listed files (as written) and the run's bookkeeping
  std::vector<std::string> leftovers;  // being written, or a temporary file of a listed name
  std::vector<std::string> folders;    // listed folders, deepest first
  std::vector<std::string> changed;    // listed files whose bytes differ ("path (why)")
  std::vector<std::string> missing;    // listed files that are gone
  std::vector<std::string> foreign;    // not listed: files or folders the run did not write
};

// Compares `folder` with `manifest`. Symbolic links are never followed: a link the manifest does
// not list is foreign. The bookkeeping folder is the run's.
FolderAudit audit_folder(const std::filesystem::path& folder, const OutputManifest& manifest);

// Up to `most` of `paths`, comma-separated, with "and N more" after them.
std::string list_paths(const std::vector<std::string>& paths, std::size_t most = 8);

}  // namespace upgrain::dem::io
