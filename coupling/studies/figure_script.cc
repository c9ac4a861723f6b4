#include "coupling/studies/figure_script.h"

#include <map>
#include <system_error>

#include "coupling/studies/plot_script.h"
#include "dem/files/output_journal.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

namespace {

// The regular files directly in `folder`, with their size and modification time.
std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> listing(const fs::path& folder) {
  std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    if (e.is_regular_file(ec)) out[e.path().filename().string()] = {e.file_size(ec), e.last_write_time(ec)};
  return out;
}

}  // namespace

FigureRun run_figure_script(const std::string& script, const fs::path& folder, const std::string& log,
                            const std::vector<std::string>& figures) {
  FigureRun r;
  const std::string path = std::string(UPGRAIN_SCRIPT_DIR) + "/" + script;
  if (!fs::exists(path) || !fs::exists("/usr/bin/python3")) return r;
  r.ran = true;
  const auto before = listing(folder);
  dem::io::note_writing(folder / log);
  for (const std::string& f : figures) dem::io::note_writing(folder / f);
  r.succeeded = run_plot_script(path, folder, folder / log);
  std::error_code ec;
  for (const std::string& f : figures) {
    if (!fs::exists(folder / f, ec)) {
      dem::io::note_removed(folder / f);  // entered before it ran, never made
    } else if (r.succeeded) {
      r.made.push_back(f);
    }
  }
  for (const auto& [name, stamp] : listing(folder)) {
    const auto it = before.find(name);
    if (it == before.end() || it->second != stamp || name == log) dem::io::note_written(folder / name);
  }
  return r;
}

}  // namespace upgrain::coupling
