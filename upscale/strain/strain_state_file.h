#pragma once
// What a checkpoint keeps of a run's grid strain (docs/restart.md), each as a group of an
// HDF5 file, and back: the reference state (t0), the last evaluation as far as the next one
// uses it (F and its validity per definition, the sets' sizes: the `previous` of grid_strain()),
// the outputs the objective stress rates difference, and the list of strain files written.
//
// Layouts:
//   reference: attributes time, step, cells; grid (9: lo, hi, n); id (int64), x (N x 3),
//     cell (int32);
//   previous: attributes set, reference_time, reference_step, time, step, untracked; grid (9);
//     particles (int64 per cell); computed (int32 per definition); per definition computed,
//     <definition>/F (cells x 9) and <definition>/F_reason (int32);
//   rate history: attribute formula (its index) and outputs; output_<k>/{time (attribute),
//     stress (cells x 9), <definition>/rotation (cells x 9), <definition>/F_reason};
//   strain files: attribute files and a table (time, step, grid (9), computed (2), rates).
#include <hdf5.h>

#include <deque>
#include <string>
#include <vector>

#include "dem/io/hdf5_reader.h"
#include "upscale/strain/grid_strain.h"
#include "upscale/strain/grid_strain_output.h"
#include "upscale/strain/grid_stress_rates.h"

namespace upgrain::upscale {

using dem::io::hdf5::Reader;

void write_strain_reference(hid_t parent, const std::string& group, const StrainReference& r);
StrainReference read_strain_reference(const Reader& in, const std::string& group);

void write_previous_strain(hid_t parent, const std::string& group, const GridStrain& g);
GridStrain read_previous_strain(const Reader& in, const std::string& group);

void write_rate_history(hid_t parent, const std::string& group, const StressRateHistory& h);
// Throws upgrain::Error when the history was kept for another stress formula than `formula`.
StressRateHistory read_rate_history(const Reader& in, const std::string& group, dem::StressFormula formula);

void write_strain_list(hid_t parent, const std::string& group, const std::vector<GridStrainEntry>& list);
std::vector<GridStrainEntry> read_strain_list(const Reader& in, const std::string& group);

}  // namespace upgrain::upscale
