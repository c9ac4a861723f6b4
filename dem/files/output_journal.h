#pragma once
// The journal of what a run writes (docs/output.md, "Manifest"): while it is open, every file
// and folder written under the output folder through this library (atomic_file.h,
// dem/io/csv_series.h) is entered in the folder's manifest (output_manifest.h), and the manifest is
// saved (renamed into place) at every change.
//
// The order makes the manifest trustworthy after a crash at any moment: a name is entered as
// being written *before* its bytes reach the folder, and gets its size and checksum after.
// So whatever the folder holds that the manifest does not list, the run did not write.
//
// One journal per process, opened by the driver on the rank that writes the run's files (rank
// 0); elsewhere, and in programs that never open one (tests, benchmarks), the calls do nothing.
// Files that other ranks write (the pieces of a parallel mesh) are entered by rank 0 around the
// collective write. Not thread-safe: the run writes from one thread.
#include <mpi.h>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "dem/files/output_manifest.h"

namespace upgrain::dem::io {

// Opens the journal of `folder` with `manifest` (a new run's, or the one a restart read back),
// and saves it. Throws upgrain::Error when it cannot be saved.
void open_output_journal(const std::filesystem::path& folder, OutputManifest manifest);
// Saves it with its final status (finished, stopped, failed) and closes it. Never throws.
void close_output_journal(const std::string& status);
[[nodiscard]] bool output_journal_open();

// `path` is about to be written (created, replaced or appended to).
void note_writing(const std::filesystem::path& path);
// `path` is complete: its size and checksum are read from disk.
void note_written(const std::filesystem::path& path);
// `n` bytes were appended to `path`, which was complete before (its checksum is continued over
// them, the file is not read again).
void note_appended(const std::filesystem::path& path, const void* data, std::size_t n);
// `folder` was made (or exists and is now used) by the run.
void note_folder(const std::filesystem::path& folder);
// `path` was removed by the run.
void note_removed(const std::filesystem::path& path);

// Files that every rank of `comm` writes its own of (a parallel mesh's pieces) into `folder`.
// Collective: rank 0 makes the folder and enters them all as being written, and no rank returns
// before it has; when it cannot, every rank throws upgrain::Error (rank 0's with the reason).
void note_pieces_writing(MPI_Comm comm, const std::filesystem::path& folder,
                         const std::vector<std::filesystem::path>& pieces);
// Once the collective write has succeeded on every rank: rank 0 reads their sizes and checksums.
void note_pieces_written(MPI_Comm comm, const std::vector<std::filesystem::path>& pieces);

// The listed files and folders now (paths relative to the output folder): what a checkpoint
// keeps, so that a restart removes what was written after it.
std::set<std::string> journal_paths();
// The open journal's manifest, if one is open.
std::optional<OutputManifest> journal_manifest();

}  // namespace upgrain::dem::io
