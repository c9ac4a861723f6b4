#include "dem/io/csv_series.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "dem/core/error.h"
#include "dem/files/atomic_file.h"
#include "dem/files/output_journal.h"

namespace upgrain::dem::io {

CsvSeries::CsvSeries(std::filesystem::path path, std::string header)
    : path_(std::move(path)), header_(std::move(header)) {}

void CsvSeries::append(const std::string& rows) {
  const long added = static_cast<long>(std::count(rows.begin(), rows.end(), '\n'));
  if (!started_) {
    write_text_atomically(path_, header_ + rows);
    started_ = true;
    rows_ += added;
    return;
  }
  if (rows.empty()) return;
  note_writing(path_);
  const int fd = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw Error("cannot append to " + path_.string() + ": " + std::strerror(errno));
  struct stat before {};
  std::size_t done = 0;
  int error = ::fstat(fd, &before) == 0 ? 0 : errno;
  while (error == 0 && done < rows.size()) {
    const ssize_t put = ::write(fd, rows.data() + done, rows.size() - done);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0)
      error = put < 0 ? errno : ENOSPC;
    else
      done += static_cast<std::size_t>(put);
  }
  // A row cut short by a full disk is taken back: the table under its name stays whole.
  if (error != 0 && done > 0 && ::ftruncate(fd, before.st_size) != 0) error = errno;
  ::close(fd);
  if (error != 0) throw Error("cannot append to " + path_.string() + ": " + std::strerror(error));
  note_appended(path_, rows.data(), rows.size());
  rows_ += added;
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
