#pragma once
// The periodic images a coarse-grained field near a face of a periodic cell needs
// (docs/coarse-graining.md, "Periodic cells"): a kernel centred within its reach of a face
// sees the grains, branches and wall contacts across it, which the state holds only at their
// wrapped positions. Plain data in, plain data out, as the rest of the coarse graining.
#include <vector>

#include "dem/core/periodic_cell.h"
#include "upscale/cg/grain_state.h"

namespace upgrain::upscale::cg {

// The lattice vectors of the images within `reach` of the cell's box: every combination of
// n_a in [-m_a, m_a] along the periodic axes (m_a = ceil(reach / L_a), one more along a sheared
// cell's shear axis, whose images across the gradient axis are slid by up to half its
// length), n != 0, as h n: n_a L_a e_a, and n_g times the offset along the shear axis
// (dem::ShearImages). In a fixed order (the last axis slowest). A reach below half of every
// length gives the 26 neighbours of the cell.
std::vector<Vec3> image_shifts(const dem::PeriodicCell& cell, double reach);

// `s` (its cell periodic) followed by the images of its grains, branches and wall contacts that
// come within `reach` of the cell's box (point_near, segment_near), lattice vector after lattice
// vector in the order of image_shifts() and each in the order of `s`. The order is the whole
// state's, so part_near() of the result keeps the fields the same bits on any rank count. An
// image carries its grain's velocity, acceleration and displacement (peculiar velocities in a
// deforming cell, docs/periodic.md) and its branch's force. The result's cell is bounded: its
// images are in. A state whose cell is bounded is returned as it is.
GrainState with_periodic_images(const GrainState& s, double reach);

}  // namespace upgrain::upscale::cg
