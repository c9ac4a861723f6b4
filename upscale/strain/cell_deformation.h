#pragma once
// A deforming periodic cell's own deformation gradient beside its grains' (docs/periodic.md,
// "Strain over a periodic cell"): the cell's F = h h0^-1 (h the cell matrix now, h0 at the
// strain's reference time) and the best-fit F of all its grains, their positions x* followed
// across the faces (periodic_kinematics.h) fitted to those at t0 (deformation_fit.h). For a grain
// set on the affine field of the cell the two agree to round-off; the difference measures how
// far the grains' mean motion departs from the cell's. Along a bounded axis (a floor) h does not
// move, so only the components between periodic axes compare. Plain functions over plain data.
#include <array>
#include <span>
#include <string>

#include "dem/core/types.h"
#include "upscale/strain/deformation_fit.h"

namespace upgrain::upscale {

using dem::GlobalId;
using dem::Mat3;
using dem::Vec3;

struct CellDeformation {
  Mat3 cell = Mat3::Identity();  // h h0^-1
  AffineFit grains;              // the best fit of all grains present at t0 and now
  // max |F_grains(i, j) - F_cell(i, j)| over i, j both periodic; NaN when the fit is not valid.
  double difference = 0.0;
};

// `reference_id`/`reference_x`: the grains at t0 (ids ascending), `id`/`x`: now (x*, ids
// ascending); grains in one of them only are left out.
CellDeformation cell_deformation(const Mat3& h0, const Mat3& h, const std::array<bool, 3>& periodic,
                                 std::span<const GlobalId> reference_id, std::span<const Vec3> reference_x,
                                 std::span<const GlobalId> id, std::span<const Vec3> x);

// The table's header and one row (time, step, F_cell row-major, F_grains row-major, difference,
// grains): cell_deformation.csv.
std::string cell_deformation_header();
std::string cell_deformation_row(double time, long step, const CellDeformation& d);

}  // namespace upgrain::upscale
