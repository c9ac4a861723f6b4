#pragma once
// How the DEM cell at a quadrature point follows a trial displacement gradient H
// (docs/femxdem.md, "The DEM cell at a quadrature point"). The engine's periodic cell is
// diagonal but for one tilt h(s, g) (Lees-Edwards images, dem/core/periodic_cell.h), so the cell
// is not deformed by F = 1 + H itself but by the upper-triangular factor R of F = Q R (Q a
// rotation, R with a positive diagonal): the cell R h0 is the cell F h0 turned rigidly by Q^T,
// so its stress turned back, Q sigma Q^T, is the stress of F exactly (objectivity; Miehe, Dettmar
// and Zaeh 2010 deform their periodic RVEs by F likewise). A plane-strain F in x-y (no z
// components off the diagonal) has R with the one tilt R(x, y): shear axis x, gradient axis y.
// A general F has tilts (x, z) and (y, z) too, which need a triclinic cell (planned): refused.
// Plain functions, tested with numbers (tests/femxdem/cell_increment_test.cc).
#include "coupling/femxdem/rve_options.h"
#include "dem/core/types.h"

namespace upgrain::coupling {

// F = Q R by Gram-Schmidt on F's columns: for a plane-strain F the z column is orthogonal to the
// first two exactly, so R's (x, z) and (y, z) entries are exactly zero. Throws
// std::invalid_argument for det F <= 0 or a non-finite F.
struct CellFactor {
  dem::Mat3 rotation = dem::Mat3::Identity();  // Q
  dem::Mat3 stretch = dem::Mat3::Identity();   // R, upper triangular, positive diagonal
};
[[nodiscard]] CellFactor upper_triangular_factor(const dem::Mat3& f);

// The shear axis s = x and gradient axis g = y of the cell's one tilt.
inline constexpr int kTiltShear = 0;
inline constexpr int kTiltGradient = 1;

// Throws std::invalid_argument naming the component when R has a tilt other than (x, y): the
// engine's cell has one (a triclinic cell is planned).
void check_one_tilt(const dem::Mat3& stretch);

// The steps of an increment Delta H (Guo and Zhao 2014): max(ceil(steps_per_unit_strain
// max |Delta H_ij|), min_steps).
[[nodiscard]] long increment_steps(const dem::Mat3& increment, const RveOptions& o);

// The constant velocity gradient L (diagonal, and L(x, y)) that takes the engine's cell from
// `from` to `to` (both diagonal but for h(x, y)) in `steps` explicit steps of dt: the engine moves
// each length by h_dd' = (1 + dt L_dd) h_dd (advanced_cell_box(), dem/core/cell_motion.h), so
// L_dd = ((to_dd / from_dd)^(1/n) - 1) / dt; and the tilt by
// h_xy' = (1 + dt L_xx) h_xy + dt L_xy h_yy (advanced_offset()), whose n steps sum to
// a^n h_xy + dt L_xy h_yy(0) sum_k a^(n-1-k) c^k (a = 1 + dt L_xx, c = 1 + dt L_yy), solved for
// L_xy. What is left: each step puts the faces and the tilt on the position grid (half a quantum,
// ~1e-16 of the cell), so the cell ends within n quanta of `to` (and the roundings of pow).
[[nodiscard]] dem::Mat3 increment_velocity_gradient(const dem::Mat3& from, const dem::Mat3& to, long steps,
                                                    double dt);

}  // namespace upgrain::coupling
