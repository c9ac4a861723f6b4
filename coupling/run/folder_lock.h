#pragma once
// An advisory lock on a run's output folder (docs/output.md, "Lock"): while a run lives, no other
// run, restart or overwrite may use its folder. The lock file is <folder>/.upgrain/lock; every
// rank of the run holds a record lock (open-file-description lock, fcntl F_OFD_SETLK) on its own
// byte of it, rank r on byte r, so the folder stays locked while any rank of the run lives, even
// after rank 0 has died. The file's text names each rank's process and host. The kernel drops
// the locks when the processes end, however they end: a killed run never leaves its folder
// locked.
#include <mpi.h>

#include <filesystem>
#include <string>

namespace upgrain::coupling {

class FolderLock {
 public:
  // Collective over `comm`: creates the folder and its lock file when missing, and locks it.
  // Throws upgrain::CollectiveError on every rank, naming the holder, when another process
  // holds it.
  FolderLock(const std::filesystem::path& folder, MPI_Comm comm);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  // Whether the lock made the folder (rank 0; it did not exist before).
  [[nodiscard]] bool made_folder() const { return made_; }

 private:
  int fd_ = -1;
  bool made_ = false;
};

// Who holds the lock of `folder` ("PID 123 on host h, rank 0 of 2, since ..."), or empty when no
// process does.
std::string lock_holder(const std::filesystem::path& folder);

}  // namespace upgrain::coupling
