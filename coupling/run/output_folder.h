#pragma once
// An output folder that holds an earlier run (docs/output.md, "Overwrite"): with
// Output/overwrite = true the new run replaces it whole, so no file of the earlier run (a later
// snapshot, a longer table, a mesh listed in strain.pvd, a checkpoint) is mixed into the new
// one. Only a folder that an Upgrain run wrote is replaced: one holding other files is refused.
#include <filesystem>
#include <string>

namespace upgrain::coupling {

// Whether `folder` holds the results of a run: its time series, summary or checkpoints.
bool holds_a_run(const std::filesystem::path& folder);

// Why overwrite may not replace `folder` (it holds no run, or a scene file, which a run never
// writes and the user would lose), or empty when it may.
std::string why_not_replaceable(const std::filesystem::path& folder);

// Empty `folder` of the earlier run: it is renamed aside first (one step, so a crash leaves
// either the whole earlier run or none of it under the folder's name), then removed. Does
// nothing when the folder is missing or empty; throws upgrain::Error naming it when it holds
// something else than a run, or cannot be moved or removed.
void replace_earlier_run(const std::filesystem::path& folder);

}  // namespace upgrain::coupling
