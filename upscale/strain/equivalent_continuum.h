#pragma once
// The "equivalent continuum" deformation and velocity gradients of a particle set (Bagi
// 1996, Mech. Mater. 22, 165-177): tessellate the centroids into Delaunay tetrahedra,
// interpolate the displacement (or velocity) linearly over each tetrahedron, and average
// its gradient over the tessellated volume. The tessellation comes from CGAL
// (Delaunay_triangulation_3), not from code of ours (docs/strain.md).
//
// For tetrahedron t with reference edge matrix dX_t = [X1-X0, X2-X0, X3-X0] and current
// dx_t, the linear map is F_t = dx_t dX_t^-1 and its volume V_t = det(dX_t) / 6, so
//   F = sum_t V_t F_t / sum_t V_t = sum_t dx_t adj(dX_t) / sum_t det(dX_t),
// which needs no inverse: slivers of near-zero volume carry near-zero weight instead of
// blowing up. An affine motion x = F X + c gives dx_t = F dX_t, hence exactly F.
// L is the same with (X, x) replaced by (x, v), over a tessellation of the current positions:
// the reference tetrahedra carried to them while none has inverted (gradient_over_carried_
// tetrahedra), else a new one.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "dem/core/types.h"

namespace upgrain::upscale {

using dem::Mat3;
using dem::Vec3;

struct TessellationGradient {
  bool valid = false;
  std::string reason;            // why not valid; empty when valid
  Mat3 gradient = Mat3::Zero();  // F or L; zero when not valid
  double volume = 0.0;           // tessellated volume (convex hull of the tessellated points)
  long tetrahedra = 0;
};

// The Delaunay tetrahedra of a point set (CGAL), as indices into the set, in CGAL's order
// of finite cells, each positively oriented. Keeping them lets F be taken again for new
// current positions of the same reference set without tessellating it again.
struct DelaunayTetrahedra {
  bool valid = false;
  std::string reason;  // why not valid; empty when valid
  std::vector<std::array<int, 4>> tetrahedra;
};

// Invalid with the reason for fewer than 4 points, non-finite values, or points that span
// less than three dimensions (the best fit's second-moment rule, then CGAL's dimension).
DelaunayTetrahedra delaunay_tetrahedra(std::span<const Vec3> points);

// The volume-averaged gradient over given tetrahedra of `reference` (from
// delaunay_tetrahedra(reference)). Invalid when the lengths differ, a current value is not
// finite, or the tetrahedra have no volume.
TessellationGradient gradient_over_tetrahedra(const DelaunayTetrahedra& tessellation,
                                              std::span<const Vec3> reference, std::span<const Vec3> current);

// The same over the tetrahedra of `tessellation` carried to new positions: the Delaunay cells
// of a set's reference positions, now spanned by its current `positions`, averaging the
// gradient of `values` (velocities: L). Valid while every tetrahedron keeps a positive volume;
// invalid with the reason "a tetrahedron has inverted" otherwise (take a new tessellation
// then), or for the reasons of gradient_over_tetrahedra(). Positive volumes do not rule out
// cells folded over one another, and the cells are no longer Delaunay, so L here depends on the
// history since the reference, not only on the current positions as a new tessellation's would.
// On each tetrahedron L_t = dF_t/dt F_t^-1 exactly, so F and L are averages over the same
// cells.
TessellationGradient gradient_over_carried_tetrahedra(const DelaunayTetrahedra& tessellation,
                                                      std::span<const Vec3> positions,
                                                      std::span<const Vec3> values);

// F from reference and current positions: the tessellation is that of the reference
// positions (delaunay_tetrahedra, then gradient_over_tetrahedra). Invalid with the reason
// (fewer than 4 points, different lengths, non-finite values, or points that span less
// than three dimensions).
TessellationGradient equivalent_continuum_deformation(std::span<const Vec3> reference,
                                                      std::span<const Vec3> current);

// L from current positions and velocities (tessellation of the current positions).
inline TessellationGradient equivalent_continuum_velocity_gradient(std::span<const Vec3> positions,
                                                                   std::span<const Vec3> velocities) {
  return equivalent_continuum_deformation(positions, velocities);
}

}  // namespace upgrain::upscale
