#pragma once
// How a periodic cell deforms (docs/periodic.md, "A cell that deforms"): its matrix h (the
// three edge vectors as columns; diagonal while the cell is orthorhombic) moves by a velocity
// gradient L, h' = L h. Each diagonal component of L is prescribed (a strain rate) or set by
// a servo to bring the cell's stress to a target (isotropic and triaxial compression). One
// off-diagonal component L(s, g) may be prescribed, a shear rate (simple shear, with the cell's
// images in the Lees-Edwards form of periodic_cell.h: ShearImages).
//
// The mean flow is L x, and the grains' equations are SLLOD's (Evans and Morriss 1990,
// Statistical Mechanics of Nonequilibrium Liquids, sec. 6.3), for the peculiar velocity u (the
// grain's motion relative to the mean flow, what the store holds): x' = u + L x, u' = F/m - L u.
// A grain with u = 0 and no force stays on the affine field x(t) = F(t) x(0), F = h(t) h(0)^-1.
//
// Plain values and functions, tested with numbers (tests/unit/cell_motion_test.cc); the
// engine (dem/engine/simulation.cc) calls them every step.
#include <algorithm>
#include <array>
#include <cmath>

#include "dem/core/box.h"
#include "dem/core/periodic_cell.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// How one diagonal component of L is set.
enum class CellAxisMode {
  fixed,  // L_dd = 0
  rate,   // L_dd prescribed (1/s; < 0 compresses)
  servo,  // L_dd = gain (p_dd - target), bounded by max_rate: p = -sigma (compression positive)
};

struct CellAxisControl {
  CellAxisMode mode = CellAxisMode::fixed;
  double rate = 0.0;             // rate: L_dd (1/s)
  double target_pressure = 0.0;  // servo: the target of -sigma_dd (Pa)
  double gain = 0.0;             // servo: 1/(Pa s)
  double max_rate = 0.0;         // servo: the bound on |L_dd| (1/s)
};

// A prescribed shear rate L(s, g) = d v_s / d x_g (1/s): the grains' mean flow slides along the
// shear axis s with the gradient axis g.
struct CellShearControl {
  std::array<int, 2> component{-1, -1};  // {s, g}; {-1, -1}: no shear
  double rate = 0.0;

  [[nodiscard]] bool any() const { return component[0] >= 0; }
  [[nodiscard]] int shear() const { return component[0]; }
  [[nodiscard]] int gradient() const { return component[1]; }
};

struct CellMotion {
  std::array<CellAxisControl, 3> axis{};
  CellShearControl shear;
  // The cell may grow up to this factor along an axis: its position grid is sized for it
  // (periodic_cell.h, make_periodic_cell()), and the engine refuses growth past it.
  double max_growth = 2.0;

  [[nodiscard]] bool any() const {
    return shear.any() || std::any_of(axis.begin(), axis.end(),
                                      [](const CellAxisControl& a) { return a.mode != CellAxisMode::fixed; });
  }
};

// The state of a deforming cell between two steps, what a checkpoint keeps: h (its diagonal
// the lengths; the off-diagonal tilt zero in this step), the corner it is spanned from, and L.
struct CellState {
  Mat3 h = Mat3::Zero();
  Vec3 origin = Vec3::Zero();
  Mat3 velocity_gradient = Mat3::Zero();
};

// The velocity gradient of the first step: the prescribed rates, the servos at rest.
inline Mat3 initial_velocity_gradient(const CellMotion& m) {
  Mat3 l = Mat3::Zero();
  for (int d = 0; d < 3; ++d)
    if (m.axis[d].mode == CellAxisMode::rate) l(d, d) = m.axis[d].rate;
  if (m.shear.any()) l(m.shear.shear(), m.shear.gradient()) = m.shear.rate;
  return l;
}

// The servo's L_dd for the cell stress sigma (tension positive, docs/stress.md): proportional
// to the pressure's excess over the target (a cell pressed too hard expands), bounded by
// max_rate, as Yade's PeriTriaxController bounds its strain rate.
inline double servo_rate(const CellAxisControl& c, double sigma_dd) {
  const double l = c.gain * (-sigma_dd - c.target_pressure);
  return std::clamp(l, -c.max_rate, c.max_rate);
}

// The velocity gradient after an evaluation of the cell stress `sigma`: the servo axes' rates
// updated, the others kept.
inline Mat3 updated_velocity_gradient(const CellMotion& m, const Mat3& current, const Mat3& sigma) {
  Mat3 l = current;
  for (int d = 0; d < 3; ++d)
    if (m.axis[d].mode == CellAxisMode::servo) l(d, d) = servo_rate(m.axis[d], sigma(d, d));
  return l;
}

// One step of h' = L h for a diagonal L, on the cell's position grid: each face's coordinate
// x goes to x + dt L x, the map the grains of the mean flow take (x + dt L x, then onto the
// grid), so that a grain on the affine field stays on it with the faces.
inline Box advanced_cell_box(const PeriodicCell& cell, const Mat3& l, double dt) {
  Box b = cell.box;
  for (int d = 0; d < 3; ++d) {
    if (!cell.periodic[d] || l(d, d) == 0.0) continue;
    b.lo[d] = on_grid(b.lo[d] + dt * l(d, d) * b.lo[d], cell.quantum[d]);
    b.hi[d] = on_grid(b.hi[d] + dt * l(d, d) * b.hi[d], cell.quantum[d]);
  }
  return b;
}

// One step of a sheared cell's tilt, h(s, g)' = L(s, s) h(s, g) + L(s, g) h(g, g) (the (s, g)
// component of h' = L h, L having no other off-diagonal component), on the grid of s, with the
// lengths of the step's start. In terms of the offset (the tilt less its turns, which the length
// L_s carries with it as it changes at L(s, s)): offset' = offset + dt (L(s, s) offset + L(s, g) L_g).
inline double advanced_offset(const PeriodicCell& cell, const Mat3& l, double dt) {
  const ShearImages& le = cell.shear;
  const int s = le.shear, g = le.gradient;
  return on_grid(le.offset + dt * (l(s, s) * le.offset + l(s, g) * cell.length(g)), cell.quantum[s]);
}

// The offset brought back within half a length of zero by whole lengths L_s, counted in the
// turns: the same lattice of images (periodic_cell.h). Exact: both are on the grid of s.
inline ShearImages remapped(ShearImages le, double length_s) {
  while (le.offset > 0.5 * length_s) {
    le.offset -= length_s;
    ++le.turns;
  }
  while (le.offset < -0.5 * length_s) {
    le.offset += length_s;
    --le.turns;
  }
  return le;
}

// The mean flow L x of a deforming cell, for an L that is diagonal but for at most one component
// L(shear, gradient): what the drift and the force loop's relative velocities take.
struct MeanFlow {
  Vec3 rate = Vec3::Zero();  // L's diagonal
  int shear = 0, gradient = 0;
  double shear_rate = 0.0;  // L(shear, gradient)

  [[nodiscard]] Vec3 of(const Vec3& x) const {
    Vec3 v = rate.cwiseProduct(x);
    if (shear_rate != 0.0) v[shear] += shear_rate * x[gradient];
    return v;
  }
};

inline MeanFlow mean_flow(const Mat3& l, const CellShearControl& c) {
  MeanFlow f;
  f.rate = l.diagonal();
  if (c.any()) {
    f.shear = c.shear();
    f.gradient = c.gradient();
    f.shear_rate = l(c.shear(), c.gradient());
  }
  return f;
}

// exp(-L tau) for such an L, applied to a peculiar velocity: SLLOD's u' = -L u over tau, exactly.
// The diagonal e^(-L_dd tau); the one off-diagonal component of the exponential of the 2 x 2 block
// [[a, b], [0, c]] = -tau [[L_ss, L_sg], [0, L_gg]] is b e^c (e^(a - c) - 1) / (a - c) (b e^a when
// a = c; Higham 2008, Functions of Matrices, sec. 4.6, the 2 x 2 triangular case).
struct FlowDecay {
  Vec3 diagonal = Vec3::Ones();
  int shear = 0, gradient = 0;
  double cross = 0.0;

  [[nodiscard]] Vec3 operator()(const Vec3& u) const {
    Vec3 w = diagonal.cwiseProduct(u);
    if (cross != 0.0) w[shear] += cross * u[gradient];
    return w;
  }
};

inline FlowDecay flow_decay(const MeanFlow& f, double tau) {
  FlowDecay d;
  d.diagonal = (-tau * f.rate).array().exp().matrix();
  d.shear = f.shear;
  d.gradient = f.gradient;
  if (f.shear_rate != 0.0) {
    const double a = -tau * f.rate[f.shear], c = -tau * f.rate[f.gradient], b = -tau * f.shear_rate;
    d.cross = b * std::exp(c) * (a == c ? 1.0 : std::expm1(a - c) / (a - c));
  }
  return d;
}

// The cell matrix: its lengths on the diagonal, a sheared cell's tilt h(s, g) besides.
inline Mat3 cell_matrix(const PeriodicCell& cell) {
  Mat3 h = (cell.box.hi - cell.box.lo).asDiagonal();
  if (cell.shear.any()) h(cell.shear.shear, cell.shear.gradient) = cell.tilt();
  return h;
}

// The cell matrix of an orthorhombic cell: its lengths on the diagonal.
inline Mat3 cell_matrix(const Box& box) { return (box.hi - box.lo).asDiagonal(); }

}  // namespace upgrain::dem
