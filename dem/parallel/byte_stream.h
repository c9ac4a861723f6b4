#pragma once
// Flat byte streams of plain data, to send a structure of mixed parts (vectors of trivially
// copyable records, strings, scalars) in one broadcast: the writer appends, the reader takes in
// the same order. Not a file format: the two ends are the same build.
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "dem/core/box.h"
#include "dem/core/error.h"
#include "dem/core/types.h"

namespace upgrain::dem {

class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* b = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), b, b + sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(static_cast<std::uint64_t>(values.size()));
    const auto* b = reinterpret_cast<const char*>(values.data());
    bytes_.insert(bytes_.end(), b, b + values.size() * sizeof(T));
  }
  void put(const std::string& s) { put(std::vector<char>(s.begin(), s.end())); }
  void put(const Vec3& v) {
    for (int d = 0; d < 3; ++d) put(v[d]);
  }
  void put(const Box& b) {
    put(b.lo);
    put(b.hi);
  }
  [[nodiscard]] std::vector<char>& bytes() { return bytes_; }

 private:
  std::vector<char> bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <class T>
  void get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    take(&value, sizeof(T));
  }
  template <class T>
  void get(std::vector<T>& values) {
    std::uint64_t n = 0;
    get(n);
    values.resize(n);
    take(values.data(), n * sizeof(T));
  }
  void get(std::string& s) {
    std::vector<char> c;
    get(c);
    s.assign(c.begin(), c.end());
  }
  void get(Vec3& v) {
    for (int d = 0; d < 3; ++d) get(v[d]);
  }
  void get(Box& b) {
    get(b.lo);
    get(b.hi);
  }

 private:
  void take(void* to, std::size_t n) {
    if (at_ + n > bytes_.size()) throw Error("byte stream: read past its end");
    if (n > 0) std::memcpy(to, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

// Collective: `bytes` of rank 0 on every rank, in chunks below 2 GB.
inline void broadcast_bytes(std::vector<char>& bytes, MPI_Comm comm) {
  std::uint64_t n = bytes.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
  bytes.resize(n);
  constexpr std::uint64_t kChunk = std::uint64_t{1} << 30;
  for (std::uint64_t s = 0; s < n; s += kChunk) {
    const std::uint64_t c = std::min(kChunk, n - s);
    MPI_Bcast(bytes.data() + s, static_cast<int>(c), MPI_BYTE, 0, comm);
  }
}

}  // namespace upgrain::dem
