#pragma once
// Files appear under their final name only when complete: they are written under a
// temporary name in the same folder and renamed (POSIX rename is atomic within a file
// system). A crash or an error leaves no half-written file under the final name.
#include <cstddef>
#include <filesystem>
#include <string>

namespace upgrain::dem::io {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path final_path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  [[nodiscard]] const std::filesystem::path& temporary_path() const { return tmp_; }
  [[nodiscard]] const std::filesystem::path& final_path() const { return final_; }
  // Renames the temporary file to its final name.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path tmp_;
  bool committed_ = false;
};

// Writes `n` bytes to `path` (created or emptied) and syncs them to the disk; throws
// upgrain::Error "cannot write <name>: <reason>" (a full disk: "No space left on device").
void write_bytes(const std::filesystem::path& path, const void* data, std::size_t n, const std::string& name);

// Creates `path` (empty) and reserves `n` bytes of the disk for it past its end (fallocate with
// FALLOC_FL_KEEP_SIZE: its size stays 0), so that a full disk or a size limit shows here, as
// "cannot write <name>: <reason>", before a writer that cannot report them cleanly (parallel
// HDF5) writes into it. A file system without fallocate reserves nothing.
void reserve_bytes(const std::filesystem::path& path, std::size_t n, const std::string& name);
// Once the file is written: syncs it to the disk and hands back what reserve_bytes() reserved
// past its end; throws "cannot write <name>: <reason>".
void sync_reserved(const std::filesystem::path& path, std::size_t n, const std::string& name);

// Writes `text` to `path` atomically.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

// Creates `folder` and its parents if missing; an Error naming the folder if it cannot.
void create_folder(const std::filesystem::path& folder);

}  // namespace upgrain::dem::io
