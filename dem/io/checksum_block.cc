#include "dem/io/checksum_block.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "dem/core/error.h"
#include "dem/files/fnv1a.h"

namespace upgrain::dem::io {

namespace {

constexpr const char* kTag = "Upgrain checksum FNV-1a-64";

// The block's text: the tag, the hash and the number of bytes it covers.
std::string block(const Fnv1a& hash, unsigned long long bytes) {
  char text[128];
  std::snprintf(text, sizeof text, "%s %s of %llu bytes\n", kTag, hash.hex().c_str(), bytes);
  return text;
}

// A file descriptor closed on every path.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

void stamp_checksum(std::vector<unsigned char>& image) {
  if (image.size() < kChecksumBlockBytes) throw Error("checksum: the file is shorter than its user block");
  Fnv1a hash;
  hash.add(image.data() + kChecksumBlockBytes, image.size() - kChecksumBlockBytes);
  const std::string text = block(hash, image.size() - kChecksumBlockBytes);
  std::fill(image.begin(), image.begin() + kChecksumBlockBytes, 0);
  std::copy(text.begin(), text.end(), image.begin());
}

void verify_checksum(const std::filesystem::path& file, const std::string& kind) {
  const std::string where = kind + " " + file.string();
  Descriptor d{::open(file.c_str(), O_RDONLY | O_CLOEXEC)};
  if (d.fd < 0) throw Error(where + ": cannot open: " + std::strerror(errno));
  std::string stored(kChecksumBlockBytes, '\0');
  if (::pread(d.fd, stored.data(), stored.size(), 0) != static_cast<ssize_t>(stored.size()))
    throw Error(where + ": shorter than its checksum block (cut short, or not a checkpoint)");
  stored.resize(std::strlen(stored.c_str()));
  if (stored.rfind(kTag, 0) != 0)
    throw Error(where + ": no checksum block (not a checkpoint of this format)");
  Fnv1a hash;
  std::string buffer(1 << 16, '\0');
  unsigned long long bytes = 0;
  for (off_t at = static_cast<off_t>(kChecksumBlockBytes);;) {
    const ssize_t got = ::pread(d.fd, buffer.data(), buffer.size(), at);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(where + ": cannot read: " + std::strerror(errno));
    if (got == 0) break;
    hash.add(buffer.data(), static_cast<std::size_t>(got));
    at += got;
    bytes += static_cast<unsigned long long>(got);
  }
  if (block(hash, bytes) != stored)
    throw Error(where +
                ": its bytes do not match its checksum (cut short or corrupted since it was written)");
}

}  // namespace upgrain::dem::io
