#pragma once
// The engine's state in a checkpoint file (docs/restart.md): EngineState
// (dem/engine/engine_state.h) as a group of an HDF5 file, and back. Every double is written
// as the same bits; records keep their layout version.
//
// Layout of the group (N particles sorted by id, H histories, W walls):
//   attributes version, step, pair_contacts, wall_contacts, rebuilds, rebuild_pending, last_overlap_ratio,
//     last_overlap_step, removed_by_relaxation, reference_mass, next_balance_step,
//     history_version; initial_<channel> for each term of the initial energy;
//   gravity (3); wall_forces (W x 3: the last evaluation's); dissipated (5 x 69 int64: the exact sums'
//   digits, damping, friction,
//     tangential stiffness change, rolling, rolling stiffness change); solver_stats (9 int64);
//   particles/{id, radius, inv_mass, inv_inertia, x, v, omega, force, torque,
//     positions_at_build} and, when present, {shape (int32), each shape's description
//     (dem/shape/shape_description.h: semi_axes for the ellipsoid), orientation (x, y, z, w),
//     inertia_body, damping_force, damping_torque, rolling_damping_torque, elastic (N x 3),
//     dissipation_share (N x 5)};
//   history/{a, b (int64), values (H x 13: tangential force and stiffness, rolling torque and
//     stiffness, normal, r_star, gap budget)};
//   walls/{point, normal, friction} with the names as attribute `names`;
//   domain/{box (2 x 3), blocks (3), planes_x, planes_y, planes_z, balance (count, last step,
//     before, after)}.
#include <hdf5.h>

#include <string>

#include "dem/engine/engine_state.h"
#include "dem/io/hdf5_reader.h"

namespace upgrain::dem::io {

void write_engine_state(hid_t parent, const std::string& group, const EngineState& s);
// Throws upgrain::Error naming the file and the object when a part is missing or of the wrong
// shape, or the version is not this build's.
EngineState read_engine_state(const hdf5::Reader& in, const std::string& group);

}  // namespace upgrain::dem::io
