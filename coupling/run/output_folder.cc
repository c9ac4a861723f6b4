#include "coupling/run/output_folder.h"

#include <unistd.h>

#include "dem/core/error.h"

namespace upgrain::coupling {

namespace fs = std::filesystem;

bool holds_a_run(const fs::path& folder) {
  std::error_code ec;
  for (const char* mark : {"time_series.csv", "summary.json", "checkpoints"})
    if (fs::exists(folder / mark, ec)) return true;
  return false;
}

std::string why_not_replaceable(const fs::path& folder) {
  if (!holds_a_run(folder))
    return "holds files but no earlier run (no time_series.csv, summary.json or checkpoints/): "
           "Output/overwrite replaces a run's folder only; choose an empty or new folder";
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    if (e.path().extension() == ".prm")
      return "holds the scene file " + e.path().filename().string() +
             ", which overwrite would remove with the earlier run; move it out of the folder";
  return {};
}

void replace_earlier_run(const fs::path& folder) {
  std::error_code ec;
  if (!fs::exists(folder, ec) || fs::is_empty(folder, ec)) return;
  if (const std::string why = why_not_replaceable(folder); !why.empty())
    throw Error("Output/folder = '" + folder.string() + "' " + why);
  fs::path aside = folder;
  aside += ".replaced." + std::to_string(::getpid());
  fs::rename(folder, aside, ec);
  if (ec) throw Error("cannot move the earlier run in " + folder.string() + " aside: " + ec.message());
  fs::remove_all(aside, ec);
  if (ec) throw Error("cannot remove the earlier run, moved to " + aside.string() + ": " + ec.message());
}

}  // namespace upgrain::coupling
