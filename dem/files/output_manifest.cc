#include "dem/files/output_manifest.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

#include "dem/core/error.h"
#include "dem/files/fnv1a.h"

namespace upgrain::dem::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kHeader =
    "# Upgrain output manifest: the files this run wrote (docs/output.md, \"Manifest\")";

std::string hex(std::uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

}  // namespace

std::string OutputManifest::to_text() const {
  std::ostringstream out;
  out << kHeader << "\nrun " << run_id << "\nscene " << scene_hash << "\nstatus " << status << "\n";
  for (const auto& [path, e] : entries) {
    if (e.kind == ManifestEntry::Kind::file)
      out << "F " << e.size << " " << hex(e.hash) << " " << path << "\n";
    else
      out << static_cast<char>(e.kind) << " - - " << path << "\n";
  }
  return out.str();
}

OutputManifest OutputManifest::parse(const std::string& text, const std::string& file) {
  OutputManifest m;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = file + ":" + std::to_string(number) + ": ";
    if (number == 1) {
      header = line == kHeader;
      if (!header) throw Error(file + ": not an Upgrain output manifest");
      continue;
    }
    if (line.empty()) continue;
    const std::size_t space = line.find(' ');
    const std::string key = line.substr(0, space);
    const std::string rest = space == std::string::npos ? "" : line.substr(space + 1);
    if (key == "run") {
      m.run_id = rest;
    } else if (key == "scene") {
      m.scene_hash = rest;
    } else if (key == "status") {
      m.status = rest;
    } else if (key == "F" || key == "W" || key == "D") {
      // <kind> <size> <checksum> <path>: the path is the rest of the line, spaces and all.
      std::istringstream fields(rest);
      std::string size, hash;
      fields >> size >> hash;
      const std::size_t at = rest.find(' ', rest.find(' ') + 1);
      if (at == std::string::npos || at + 1 >= rest.size()) throw Error(where + "an entry without a path");
      const std::string path = rest.substr(at + 1);
      ManifestEntry e;
      e.kind = static_cast<ManifestEntry::Kind>(key[0]);
      if (e.kind == ManifestEntry::Kind::file) {
        try {
          std::size_t used = 0;
          e.size = std::stoull(size, &used);
          if (used != size.size()) throw std::invalid_argument(size);
          e.hash = std::stoull(hash, &used, 16);
          if (used != hash.size() || hash.size() != 16) throw std::invalid_argument(hash);
        } catch (const std::exception&) {
          throw Error(where + "'" + size + " " + hash + "' is not a size and a checksum");
        }
      }
      m.entries[path] = e;
    } else {
      throw Error(where + "unknown line '" + key + "'");
    }
  }
  if (!header) throw Error(file + ": empty, not an Upgrain output manifest");
  if (m.run_id.empty()) throw Error(file + ": names no run");
  return m;
}

fs::path manifest_path(const fs::path& folder) { return folder / kBookkeepingFolder / "manifest"; }

bool has_manifest(const fs::path& folder) {
  std::error_code ec;
  return fs::is_regular_file(manifest_path(folder), ec);
}

OutputManifest read_manifest(const fs::path& folder) {
  const fs::path file = manifest_path(folder);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": cannot open: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return OutputManifest::parse(text.str(), file.string());
}

FileDigest digest_file(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error("cannot read " + file.string() + ": " + std::strerror(errno));
  FileDigest d;
  Fnv1a hash;
  std::string buffer(1 << 16, '\0');
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int e = errno;
      ::close(fd);
      throw Error("cannot read " + file.string() + ": " + std::strerror(e));
    }
    if (got == 0) break;
    hash.add(buffer.data(), static_cast<std::size_t>(got));
    d.size += static_cast<std::uint64_t>(got);
  }
  ::close(fd);
  d.hash = hash.value();
  return d;
}

FolderAudit audit_folder(const fs::path& folder, const OutputManifest& manifest) {
  using Kind = ManifestEntry::Kind;
  static const std::regex temporary(R"((.*)\.tmp\.\d+)");
  FolderAudit a;
  std::error_code ec;
  // Depth first, without following links. A folder being written is not entered (all of it is a
  // leftover).
  std::vector<fs::path> pending{folder};
  while (!pending.empty()) {
    const fs::path dir = pending.back();
    pending.pop_back();
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
      const std::string rel = e.path().lexically_relative(folder).generic_string();
      const fs::file_status st = e.symlink_status(ec);
      const bool is_dir = fs::is_directory(st);
      if (rel == kBookkeepingFolder) {
        a.ours.push_back(rel + "/");
        continue;
      }
      const auto it = manifest.entries.find(rel);
      if (it != manifest.entries.end()) {
        const ManifestEntry& m = it->second;
        if (m.kind == Kind::being_written) {
          a.leftovers.push_back(rel);
        } else if (m.kind == Kind::folder) {
          if (is_dir) {
            a.folders.push_back(rel);
            pending.push_back(e.path());
          } else {
            a.changed.push_back(rel + " (the run made a folder here)");
          }
        } else if (!fs::is_regular_file(st)) {
          a.changed.push_back(rel + " (no longer a regular file)");
        } else {
          const FileDigest d = digest_file(e.path());
          if (d.size != m.size)
            a.changed.push_back(rel + " (" + std::to_string(d.size) + " bytes, the run wrote " +
                                std::to_string(m.size) + ")");
          else if (d.hash != m.hash)
            a.changed.push_back(rel + " (its bytes differ from those the run wrote)");
          else
            a.ours.push_back(rel);
        }
        continue;
      }
      std::smatch t;
      if (std::regex_match(rel, t, temporary) && manifest.entries.count(t[1].str()) > 0) {
        a.leftovers.push_back(rel);
        continue;
      }
      // A folder the run did not make but wrote into (it was there before) is entered, and only
      // what is foreign in it is named; one that holds nothing of the run is named whole.
      const std::string prefix = rel + "/";
      const auto under = manifest.entries.lower_bound(prefix);
      if (is_dir && under != manifest.entries.end() && under->first.compare(0, prefix.size(), prefix) == 0)
        pending.push_back(e.path());
      else
        a.foreign.push_back(is_dir ? prefix : rel);
    }
  }
  for (const auto& [path, m] : manifest.entries) {
    if (m.kind != Kind::file) continue;
    if (!fs::exists(fs::symlink_status(folder / path, ec))) a.missing.push_back(path);
  }
  for (std::vector<std::string>* v : {&a.ours, &a.leftovers, &a.changed, &a.missing, &a.foreign})
    std::sort(v->begin(), v->end());
  // Deepest first, so that a folder is emptied before its parent.
  std::sort(a.folders.begin(), a.folders.end(), [](const std::string& x, const std::string& y) {
    const auto depth = [](const std::string& s) { return std::count(s.begin(), s.end(), '/'); };
    return depth(x) != depth(y) ? depth(x) > depth(y) : x < y;
  });
  return a;
}

std::string list_paths(const std::vector<std::string>& paths, std::size_t most) {
  std::string out;
  for (std::size_t k = 0; k < paths.size() && k < most; ++k) out += (k ? ", " : "") + paths[k];
  if (paths.size() > most) out += " and " + std::to_string(paths.size() - most) + " more";
  return out;
}

}  // namespace upgrain::dem::io
