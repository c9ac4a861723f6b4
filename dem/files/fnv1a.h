#pragma once
// 64-bit FNV-1a (Fowler, Noll and Vo): no defence against an adversary, but every changed byte
// changes it, it needs no library, and it streams: the hash of a file grown by appending is the
// hash of its old bytes continued over the new ones. Used for the checkpoints' checksum block,
// the scene's hash and the output manifest's file checksums (docs/output.md, "Manifest").
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace upgrain::dem::io {

class Fnv1a {
 public:
  static constexpr std::uint64_t kOffsetBasis = 14695981039346656037ULL;

  Fnv1a() = default;
  // Continues a hash from its value: the bytes already hashed need not be read again.
  explicit Fnv1a(std::uint64_t value) : hash_(value) {}

  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) {
      hash_ ^= p[k];
      hash_ *= 1099511628211ULL;
    }
  }
  void add(const std::string& s) { add(s.data(), s.size()); }

  [[nodiscard]] std::uint64_t value() const { return hash_; }
  // 16 lower-case hex digits.
  [[nodiscard]] std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
    return text;
  }

 private:
  std::uint64_t hash_ = kOffsetBasis;
};

}  // namespace upgrain::dem::io
