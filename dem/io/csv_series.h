#pragma once
// A CSV time series that grows by appending: the first rows are written with the header
// atomically (atomic_file.h), later rows are appended with one write per call and flushed.
// So a long run costs O(rows) in output, not O(rows^2) as rewriting the table at every
// evaluation would. A crash during an append can cut the last row short, never an
// earlier one.
#include <filesystem>
#include <string>

namespace upgrain::dem::io {

class CsvSeries {
 public:
  // Nothing is written until the first append.
  CsvSeries(std::filesystem::path path, std::string header);
  // `rows`: complete lines, each ending in '\n'. Throws upgrain::Error naming the file.
  void append(const std::string& rows);
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::string header_;
  bool started_ = false;
};

}  // namespace upgrain::dem::io
