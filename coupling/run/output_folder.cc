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

void replace_earlier_run(const fs::path& folder) {
  std::error_code ec;
  if (!fs::exists(folder, ec) || fs::is_empty(folder, ec)) return;
  if (!holds_a_run(folder))
    throw Error("Output/overwrite = true, but " + folder.string() +
                " holds no earlier run (no time_series.csv, summary.json or checkpoints/) and is not empty: "
                "overwrite replaces a run's folder only; choose an empty or new folder");
  fs::path aside = folder;
  aside += ".replaced." + std::to_string(::getpid());
  fs::rename(folder, aside, ec);
  if (ec) throw Error("cannot move the earlier run in " + folder.string() + " aside: " + ec.message());
  fs::remove_all(aside, ec);
  if (ec) throw Error("cannot remove the earlier run, moved to " + aside.string() + ": " + ec.message());
}

}  // namespace upgrain::coupling
