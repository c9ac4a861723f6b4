#include "dem/io/csv_series.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "dem/core/error.h"
#include "dem/io/atomic_file.h"

namespace upgrain::dem::io {

CsvSeries::CsvSeries(std::filesystem::path path, std::string header)
    : path_(std::move(path)), header_(std::move(header)) {}

void CsvSeries::append(const std::string& rows) {
  if (!started_) {
    write_text_atomically(path_, header_ + rows);
    started_ = true;
    return;
  }
  if (rows.empty()) return;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path_.c_str(), "ab"), std::fclose);
  if (!f) throw Error("cannot append to " + path_.string() + ": " + std::strerror(errno));
  if (std::fwrite(rows.data(), 1, rows.size(), f.get()) != rows.size() || std::fflush(f.get()) != 0)
    throw Error("cannot append to " + path_.string() + ": " + std::strerror(errno));
}

}  // namespace upgrain::dem::io
