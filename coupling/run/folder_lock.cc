#include "coupling/run/folder_lock.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <vector>

#include "coupling/run/output_folder.h"
#include "dem/core/error.h"
#include "dem/files/output_manifest.h"
#include "dem/parallel/exchange.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

namespace {

fs::path lock_path(const fs::path& folder) { return folder / dem::io::kBookkeepingFolder / "lock"; }

struct flock byte_lock(short type, off_t start, off_t length) {
  struct flock l {};
  l.l_type = type;
  l.l_whence = SEEK_SET;
  l.l_start = start;
  l.l_len = length;  // 0: to the end of any file
  return l;
}

// The line of the lock file's text that names rank `rank`'s holder, or a plain description.
std::string holder_from_text(int fd, off_t rank) {
  std::string text(4096, '\0');
  const ssize_t got = ::pread(fd, text.data(), text.size(), 0);
  text.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
  std::istringstream in(text);
  std::string line, since;
  while (std::getline(in, line)) {
    if (line.rfind("since ", 0) == 0) since = line.substr(6);
    // "rank <r> of <n>: PID <p> on host <h>"
    const std::size_t colon = line.find(": ");
    if (line.rfind("rank " + std::to_string(rank) + " ", 0) == 0 && colon != std::string::npos)
      return line.substr(colon + 2) + ", " + line.substr(0, colon) +
             (since.empty() ? "" : ", since " + since);
  }
  return "rank " + std::to_string(rank) + " of a run whose lock file names no process";
}

// The holder of any byte of the lock file open as `fd`, or empty.
std::string holder(int fd) {
  struct flock l = byte_lock(F_WRLCK, 0, 0);
  if (::fcntl(fd, F_OFD_GETLK, &l) != 0 || l.l_type == F_UNLCK) return {};
  return holder_from_text(fd, l.l_start);
}

}  // namespace

std::string lock_holder(const fs::path& folder) {
  const int fd = ::open(lock_path(folder).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};
  const std::string who = holder(fd);
  ::close(fd);
  return who;
}

FolderLock::FolderLock(const fs::path& folder, MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const fs::path file = lock_path(folder);
  const std::string entry = "Output/folder = '" + folder.string() + "'";
  // Rank 0 first: it makes the file, and finds out whether any process holds any byte of it.
  std::string error;
  if (rank == 0) {
    std::error_code ec;
    made_ = !fs::exists(folder, ec);
    fs::create_directories(file.parent_path(), ec);
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (ec || fd_ < 0) {
      error = entry + ": cannot create its lock file " + file.string() + ": " +
              (ec ? ec.message() : std::string(std::strerror(errno)));
    } else {
      struct flock l = byte_lock(F_WRLCK, 0, 1);
      std::string who = holder(fd_);
      int why = 0;
      if (who.empty() && ::fcntl(fd_, F_OFD_SETLK, &l) != 0) {
        why = errno;
        who = holder(fd_);
      }
      if (!who.empty())
        error = entry + " is in use by another run of upgrain (" + who +
                "); wait for it to end, or stop it (SIGINT or SIGTERM stop it after a checkpoint)";
      else if (why != 0)  // a file system without record locks: the folder cannot be kept safe
        error = entry + ": cannot lock " + file.string() + ": " + std::strerror(why);
    }
  }
  dem::throw_if_any(comm, error);
  if (rank != 0) {
    fd_ = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
    struct flock l = byte_lock(F_WRLCK, rank, 1);
    if (fd_ < 0 || ::fcntl(fd_, F_OFD_SETLK, &l) != 0)
      error = entry + ": rank " + std::to_string(rank) + " cannot lock " + file.string() + ": " +
              std::strerror(errno);
  }
  // Each rank's process and host, into the file's text for whoever finds it locked.
  std::array<char, 320> mine{};
  std::snprintf(mine.data(), mine.size(), "PID %d on host %s", static_cast<int>(::getpid()),
                host_name().c_str());
  std::vector<char> all(rank == 0 ? mine.size() * static_cast<std::size_t>(ranks) : 0);
  MPI_Gather(mine.data(), static_cast<int>(mine.size()), MPI_CHAR, all.data(), static_cast<int>(mine.size()),
             MPI_CHAR, 0, comm);
  if (rank == 0) {
    std::ostringstream text;
    text << "# upgrain: this folder is locked by the run below while it lives (docs/output.md, \"Lock\")\n"
         << "since " << utc_now("%Y-%m-%d %H:%M:%S UTC") << "\n";
    for (int r = 0; r < ranks; ++r)
      text << "rank " << r << " of " << ranks << ": "
           << all.data() + static_cast<std::size_t>(r) * mine.size() << "\n";
    const std::string t = text.str();
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, t.data(), t.size(), 0) != static_cast<ssize_t>(t.size()))
      error = entry + ": cannot write its lock file " + file.string() + ": " + std::strerror(errno);
  }
  dem::throw_if_any(comm, error);
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace upgrain::coupling
