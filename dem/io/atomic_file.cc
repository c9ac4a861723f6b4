#include "dem/io/atomic_file.h"

#include <unistd.h>
#include <fstream>
#include <system_error>

#include "dem/core/error.h"

namespace upgrain::dem::io {

AtomicFile::AtomicFile(std::filesystem::path final_path) : final_(std::move(final_path)) {
  tmp_ = final_;
  tmp_ += ".tmp." + std::to_string(::getpid());
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(tmp_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  std::filesystem::rename(tmp_, final_, ec);
  if (ec) throw Error("cannot rename " + tmp_.string() + " to " + final_.string() + ": " + ec.message());
  committed_ = true;
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  AtomicFile f(path);
  {
    std::ofstream out(f.temporary_path(), std::ios::binary);
    if (!out) throw Error("cannot write " + f.temporary_path().string());
    out << text;
    out.flush();
    if (!out) throw Error("error while writing " + f.temporary_path().string());
  }
  f.commit();
}

void create_folder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw Error("cannot create folder " + folder.string() + ": " + ec.message());
}

}  // namespace upgrain::dem::io
