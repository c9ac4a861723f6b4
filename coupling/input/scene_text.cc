#include "coupling/input/scene_text.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "dem/core/error.h"
#include "dem/io/file_kind.h"

namespace upgrain::coupling {

namespace {

// Length of the UTF-8 sequence starting at s[i] (RFC 3629: no overlong forms, no surrogates,
// at most U+10FFFF), or 0 when it is not one.
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > s.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

std::string decode_scene_text(const std::string& bytes, const std::string& source) {
  static const std::string mark = "\xEF\xBB\xBF";
  const std::size_t start = bytes.compare(0, mark.size(), mark) == 0 ? mark.size() : 0;
  std::string text;
  text.reserve(bytes.size());
  int line = 1;
  for (std::size_t i = start; i < bytes.size();) {
    const char c = bytes[i];
    if (c == '\r' && i + 1 < bytes.size() && bytes[i + 1] == '\n') {
      ++i;
      continue;
    }
    const std::size_t n = c == '\0' ? 0 : utf8_length(bytes, i);
    if (n == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(c)));
      throw Error(
          source + ":" + std::to_string(line) + ": byte " + hex +
          (c == '\0' ? " (NUL): a scene file is text" : " is not UTF-8: save the file as UTF-8 text"));
    }
    if (c == '\n') ++line;
    text.append(bytes, i, n);
    i += n;
  }
  return text;
}

std::string read_scene_bytes(const std::string& path) {
  // Asked before opening: open() of a FIFO without a writer waits for one.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw Error(path + ": cannot open the parameter file: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw Error(path + ": is " + dem::io::kind_of(st.st_mode) + ", not a parameter file");
  if (st.st_size > kMaxSceneBytes)
    throw Error(path + ": " + std::to_string(st.st_size) + " bytes, more than a scene file holds (at most " +
                std::to_string(kMaxSceneBytes) + ")");
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error(path + ": cannot open the parameter file: " + std::strerror(errno));
  // The name may have been given to another file since stat(): the one opened counts.
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(path + ": is " + dem::io::kind_of(st.st_mode) + ", not a parameter file");
  }
  std::string bytes;
  char buffer[65536];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int e = errno;
      ::close(fd);
      throw Error(path + ": cannot read the parameter file: " + std::strerror(e));
    }
    if (got == 0) break;
    bytes.append(buffer, static_cast<std::size_t>(got));
    if (static_cast<long>(bytes.size()) > kMaxSceneBytes) {
      ::close(fd);
      throw Error(path + ": more than " + std::to_string(kMaxSceneBytes) +
                  " bytes, more than a scene file holds");
    }
  }
  ::close(fd);
  return bytes;
}

}  // namespace upgrain::coupling
