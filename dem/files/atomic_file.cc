#include "dem/files/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>
#include <vector>

#include "dem/core/error.h"
#include "dem/files/output_journal.h"

namespace upgrain::dem::io {

AtomicFile::AtomicFile(std::filesystem::path final_path) : final_(std::move(final_path)) {
  tmp_ = final_;
  tmp_ += ".tmp." + std::to_string(::getpid());
  note_writing(final_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(tmp_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  std::filesystem::rename(tmp_, final_, ec);
  if (ec) throw Error("cannot rename " + tmp_.string() + " to " + final_.string() + ": " + ec.message());
  committed_ = true;
  note_written(final_);
}

void write_bytes(const std::filesystem::path& path, const void* data, std::size_t n,
                 const std::string& name) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error("cannot write " + name + ": " + std::strerror(errno));
  const char* p = static_cast<const char*>(data);
  std::size_t done = 0;
  while (done < n) {
    const ssize_t put = ::write(fd, p + done, n - done);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) {
      const int e = put < 0 ? errno : ENOSPC;
      ::close(fd);
      throw Error("cannot write " + name + ": " + std::strerror(e));
    }
    done += static_cast<std::size_t>(put);
  }
  // A file whose bytes are still in the page cache can be lost whole in a crash after its
  // rename; the error of a delayed write shows here or at close.
  const bool synced = ::fsync(fd) == 0;
  const int e = errno;
  if (::close(fd) != 0 || !synced)
    throw Error("cannot write " + name + ": " + std::strerror(synced ? errno : e));
}

void reserve_bytes(const std::filesystem::path& path, std::size_t n, const std::string& name) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw Error("cannot write " + name + ": " + std::strerror(errno));
  int e = 0;
  if (n > 0 && ::fallocate(fd, FALLOC_FL_KEEP_SIZE, 0, static_cast<off_t>(n)) != 0 && errno != EOPNOTSUPP)
    e = errno;
  ::close(fd);
  if (e != 0) throw Error("cannot write " + name + ": " + std::strerror(e));
}

void sync_reserved(const std::filesystem::path& path, std::size_t n, const std::string& name) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw Error("cannot write " + name + ": " + std::strerror(errno));
  struct stat st {};
  bool ok = ::fstat(fd, &st) == 0;
  // The blocks reserved past the end are freed (a hole beyond the end keeps the size).
  if (ok && static_cast<std::size_t>(st.st_size) < n)
    ok = ::fallocate(fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, st.st_size,
                     static_cast<off_t>(n) - st.st_size) == 0 ||
         errno == EOPNOTSUPP;
  ok = ok && ::fsync(fd) == 0;
  const int e = errno;
  if (::close(fd) != 0 || !ok) throw Error("cannot write " + name + ": " + std::strerror(ok ? errno : e));
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  AtomicFile f(path);
  write_bytes(f.temporary_path(), text.data(), text.size(), path.string());
  f.commit();
}

void create_folder(const std::filesystem::path& folder) {
  std::error_code ec;
  // Each folder it makes is entered in the output manifest, parents first.
  std::vector<std::filesystem::path> made;
  for (std::filesystem::path f = folder; !f.empty() && !std::filesystem::exists(f, ec); f = f.parent_path()) {
    made.push_back(f);
    if (f == f.parent_path()) break;
  }
  for (auto it = made.rbegin(); it != made.rend(); ++it) note_folder(*it);
  std::filesystem::create_directories(folder, ec);
  if (ec) throw Error("cannot create folder " + folder.string() + ": " + ec.message());
}

}  // namespace upgrain::dem::io
