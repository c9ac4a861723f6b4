#pragma once
// What a path a user gave names (docs/input.md, "What is read"), asked of stat() before the
// file is opened: open() of a FIFO without a writer waits for one, a device such as /dev/zero
// can be read forever, and a folder or a symbolic link loop is no file. The scene file's
// reader, the packing's and --restart's folder say what the path really is from this.
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace upgrain::dem::io {

// "a folder", "a FIFO (named pipe)", ...: what a file of `mode` is, for "X is <kind>".
inline std::string kind_of(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

struct PathKind {
  bool exists = false;  // stat() succeeded
  mode_t mode = 0;
  // With `exists`: kind_of(mode). Otherwise why stat() failed: "does not exist", "is a symbolic
  // link loop (Too many levels of symbolic links)", or the system's reason.
  std::string description;

  [[nodiscard]] bool regular() const { return exists && S_ISREG(mode); }
  [[nodiscard]] bool folder() const { return exists && S_ISDIR(mode); }
};

// `path` followed through its symbolic links.
inline PathKind path_kind(const std::string& path) {
  PathKind k;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    k.exists = true;
    k.mode = st.st_mode;
    k.description = kind_of(st.st_mode);
    return k;
  }
  const int e = errno;
  if (e == ENOENT)
    k.description = "does not exist";
  else if (e == ELOOP)
    k.description = std::string("is a symbolic link loop (") + std::strerror(e) + ")";
  else
    k.description = std::string("cannot be reached: ") + std::strerror(e);
  return k;
}

}  // namespace upgrain::dem::io
