#pragma once
// The grains and contacts each rank needs for the fields at its own points
// (docs/coarse-graining.md, "In parallel"). The points are where the continuum lives, split
// as its mesh is (p4est); the DEM's blocks are split otherwise, and its ghost layer (one
// interaction range) is thinner than a kernel (3 w). So the state gathered on rank 0 for the
// run's output is cut, per rank, to the part within a kernel's reach of that rank's points
// (part_near) and sent to it: O(N) on rank 0, O(N / P + halo) on each other rank.
#include <mpi.h>

#include <span>

#include "upscale/cg/grain_state.h"

namespace upgrain::upscale::cg {

// Collective. `whole` is read on rank 0 only (the others may pass an empty state); returns
// the part of it within `range` of the bounding box of this rank's `points` (empty when the
// rank has none). The parts keep the whole state's order and longest branch, so the fields
// are the same bits on any number of ranks. A periodic state (its cell) gets its images within
// `range` of the cell first (with_periodic_images): the parts hold them, with a bounded cell.
GrainState state_for_points(const GrainState& whole, std::span<const Vec3> points, double range,
                            MPI_Comm comm);

// Serialised form of a state (for the messages; the tests check the round trip).
std::vector<char> pack(const GrainState& s);
GrainState unpack(const std::vector<char>& bytes);

}  // namespace upgrain::upscale::cg
