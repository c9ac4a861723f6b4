#pragma once
// The studies of the driver, one row each (study_table.cc); `upgrain --study NAME` picks one,
// and without --study the first runs.
#include <span>
#include <string>
#include <string_view>

#include "coupling/studies/study.h"

namespace upgrain::coupling {

std::span<const Study> studies();

// The row named `name`. Throws upgrain::CollectiveError naming the known studies.
const Study& study_named(std::string_view name);

// "continuum, accuracy, calibration": the names, for messages.
std::string study_names();

}  // namespace upgrain::coupling
