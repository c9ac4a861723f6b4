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
  // The data rows written so far (header lines not counted).
  [[nodiscard]] long rows() const { return rows_; }
  // A restart (docs/restart.md): the file is cut back, atomically, to its header and its first
  // `rows` data rows, and later appends go after them. With 0 rows and no file, nothing is
  // written until the first append. Throws upgrain::Error naming the file when it does not
  // begin with this header or holds fewer rows.
  void resume(long rows);

 private:
  std::filesystem::path path_;
  std::string header_;
  bool started_ = false;
  long rows_ = 0;
};

}  // namespace upgrain::dem::io
