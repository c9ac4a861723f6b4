#pragma once
// The kinematics the strain of a periodic cell's grains takes (docs/periodic.md, "Strain over a
// periodic cell"). A grain is followed from the image of the cell it was in at the strain's
// reference time t0, continuously across the faces and a sheared cell's remaps:
//   x* = x + h (n - n0),
// x its wrapped position, n its image counter now and n0 at t0, h the cell matrix now (its tilt
// included: dem::unwrapped()). x* = x at t0, so that the reference positions stay in the cell and
// on its grid. An affine motion of the cell, h(t) = F h(t0), carries x*(t0) to F x*(t0): the
// lattice vectors h n0 that a wrap would otherwise leave behind deform with the cell.
// In a cell with a velocity gradient L the engine keeps each grain's peculiar velocity u, and the
// velocity of x* is u + L x* (the time derivative of x + h (n - n0) with dh/dt = L h, the drift
// carrying x at u + L x). Plain functions over plain data.
#include <span>
#include <vector>

#include "dem/core/periodic_cell.h"
#include "dem/core/types.h"

namespace upgrain::upscale {

using dem::GlobalId;
using dem::ImageCount;
using dem::Mat3;
using dem::Vec3;

struct PeriodicKinematics {
  std::vector<Vec3> x;  // x*, in the order of the input
  std::vector<Vec3> v;  // u + L x*
};

// `id`, `x`, `u`, `image`: the grains now, ids ascending; `reference_id`, `reference_image`:
// the grains at t0, ids ascending. A grain not there at t0 (poured since) is followed from its
// image now. `l`: the velocity gradient (zero for a fixed cell).
PeriodicKinematics periodic_kinematics(const dem::PeriodicCell& cell, const Mat3& l,
                                       std::span<const GlobalId> id, std::span<const Vec3> x,
                                       std::span<const Vec3> u, std::span<const ImageCount> image,
                                       std::span<const GlobalId> reference_id,
                                       std::span<const ImageCount> reference_image);

}  // namespace upgrain::upscale
