#include "dem/io/csv_series.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "dem/core/error.h"
#include "dem/io/atomic_file.h"

namespace upgrain::dem::io {

CsvSeries::CsvSeries(std::filesystem::path path, std::string header)
    : path_(std::move(path)), header_(std::move(header)) {}

void CsvSeries::append(const std::string& rows) {
  rows_ += static_cast<long>(std::count(rows.begin(), rows.end(), '\n'));
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

void CsvSeries::resume(long rows) {
  std::error_code ec;
  if (rows == 0 && !std::filesystem::exists(path_, ec)) {
    started_ = false;
    rows_ = 0;
    return;
  }
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw Error("cannot resume " + path_.string() + ": it cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  if (all.compare(0, header_.size(), header_) != 0)
    throw Error("cannot resume " + path_.string() + ": it does not begin with the expected header");
  std::size_t end = header_.size();
  for (long r = 0; r < rows; ++r) {
    const std::size_t eol = all.find('\n', end);
    if (eol == std::string::npos)
      throw Error("cannot resume " + path_.string() + ": it holds " + std::to_string(r) +
                  " rows, the checkpoint " + std::to_string(rows));
    end = eol + 1;
  }
  write_text_atomically(path_, all.substr(0, end));
  started_ = true;
  rows_ = rows;
}

}  // namespace upgrain::dem::io
