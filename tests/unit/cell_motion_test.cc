// The deforming cell's kernel with numbers (dem/core/cell_motion.h, docs/periodic.md).
#include "dem/core/cell_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

using namespace upgrain::dem;

// The servo squeezes a cell below its target pressure and lets one above it expand, at most at
// its bound; p = -sigma (tension positive).
TEST(CellMotion, ServoMovesTowardsTheTargetWithinItsBound) {
  CellAxisControl c{CellAxisMode::servo, 0.0, 1e4, 1e-4, 0.5};
  EXPECT_DOUBLE_EQ(servo_rate(c, -0.9e4), 1e-4 * (0.9e4 - 1e4));  // too loose: L < 0
  EXPECT_LT(servo_rate(c, -0.9e4), 0.0);
  EXPECT_GT(servo_rate(c, -1.2e4), 0.0);       // too dense: expands
  EXPECT_DOUBLE_EQ(servo_rate(c, 0.0), -0.5);  // bounded
  EXPECT_DOUBLE_EQ(servo_rate(c, -1e9), 0.5);
  EXPECT_DOUBLE_EQ(servo_rate(c, -1e4), 0.0);  // at the target
  CellMotion m;
  m.axis[1] = c;
  m.axis[2] = {CellAxisMode::rate, -2.0};
  const Mat3 l0 = initial_velocity_gradient(m);
  EXPECT_EQ(l0, Vec3(0.0, 0.0, -2.0).asDiagonal().toDenseMatrix());
  Mat3 sigma = Mat3::Zero();
  sigma(1, 1) = -2e4;
  const Mat3 l1 = updated_velocity_gradient(m, l0, sigma);
  EXPECT_DOUBLE_EQ(l1(1, 1), 0.5);
  EXPECT_DOUBLE_EQ(l1(2, 2), -2.0);  // the prescribed rate stays
  EXPECT_DOUBLE_EQ(l1(0, 0), 0.0);
  EXPECT_TRUE(m.any());
  EXPECT_FALSE(CellMotion{}.any());
}

// One step of h' = L h moves each face's coordinate x to x + dt L x on the grid, and leaves a
// fixed axis alone; the cell's grid, sized for twice the cell, still holds it.
TEST(CellMotion, FacesTakeTheMeanFlowsMapOnTheGrid) {
  Box b;
  b.lo = Vec3(0.0, -0.01, 0.0);
  b.hi = Vec3(0.03, 0.02, 0.05);
  const PeriodicCell cell = make_periodic_cell(b, {true, true, false}, 2.0);
  Mat3 l = Mat3::Zero();
  l(0, 0) = -3.0;
  l(1, 1) = 1.0;
  l(2, 2) = 7.0;  // a walled axis: not moved
  const double dt = 1e-4;
  const Box n = advanced_cell_box(cell, l, dt);
  EXPECT_EQ(n.lo[0], 0.0);
  EXPECT_NEAR(n.hi[0], 0.03 * (1.0 - 3e-4), cell.quantum[0]);
  EXPECT_EQ(n.hi[0], on_grid(n.hi[0], cell.quantum[0]));
  EXPECT_NEAR(n.lo[1], -0.01 * (1.0 + 1e-4), cell.quantum[1]);
  EXPECT_NEAR(n.hi[1], 0.02 * (1.0 + 1e-4), cell.quantum[1]);
  EXPECT_EQ(n.hi[2], 0.05);
  EXPECT_TRUE(grid_holds(cell, n));
  // The fixed cell's grid is finer, and the growth allowance is what it costs.
  const PeriodicCell fixed = make_periodic_cell(b, {true, true, false});
  EXPECT_EQ(cell.quantum[0], 2.0 * fixed.quantum[0]);
  Box grown = b;
  grown.hi[0] = 4.0 * b.hi[0];
  EXPECT_FALSE(grid_holds(cell, grown));
  EXPECT_EQ(cell_matrix(b), Vec3(0.03, 0.03, 0.05).asDiagonal().toDenseMatrix());
}

// A sheared cell's tilt: h(s, g)' = L(s, s) h(s, g) + L(s, g) h(g, g) per step on the grid of s;
// its remaps by whole lengths keep the tilt (offset + turns L_s) and the offset within half a
// length; the shear rate enters L(s, g) and makes the motion non-trivial.
TEST(CellMotion, ShearTiltFollowsTheVelocityGradientAndRemapsByWholeLengths) {
  CellMotion m;
  m.shear = {{0, 2}, 4.0};
  EXPECT_TRUE(m.any());
  const Mat3 l0 = initial_velocity_gradient(m);
  EXPECT_EQ(l0(0, 2), 4.0);
  EXPECT_EQ(l0(2, 0), 0.0);
  Box b;
  b.hi = Vec3(0.03, 0.02, 0.05);
  PeriodicCell cell = make_periodic_cell(b, {true, true, true}, 2.0);
  cell.shear.shear = 0;
  cell.shear.gradient = 2;
  Mat3 l = l0;
  l(0, 0) = -2.0;  // the shear axis shortens as it shears
  const double dt = 1e-4;
  double expected = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double next = advanced_offset(cell, l, dt);
    EXPECT_NEAR(next, cell.shear.offset + dt * (-2.0 * cell.shear.offset + 4.0 * 0.05), cell.quantum[0]);
    EXPECT_EQ(next, on_grid(next, cell.quantum[0]));
    expected += dt * (-2.0 * expected + 4.0 * 0.05);
    cell.shear.offset = next;
  }
  EXPECT_NEAR(cell.shear.offset, expected, 1000 * cell.quantum[0]);
  // h_sg(t) = (L_sg L_g / -L_ss)(1 - e^(L_ss t)) at t = 0.1 s, to the scheme's first order.
  EXPECT_NEAR(cell.tilt(), 0.1 * (1.0 - std::exp(-0.2)), 2e-6);
  // Past half a length: remapped by whole lengths, the tilt the same bits.
  cell.shear.offset = on_grid(0.071, cell.quantum[0]);
  const double tilt = cell.tilt();
  const ShearImages r = remapped(cell.shear, cell.length(0));
  EXPECT_EQ(r.turns, 2);
  EXPECT_LE(std::abs(r.offset), 0.5 * cell.length(0));
  PeriodicCell after = cell;
  after.shear = r;
  EXPECT_EQ(after.tilt(), tilt);
  EXPECT_EQ(cell_matrix(after)(0, 2), tilt);
  EXPECT_EQ(remapped(after.shear, cell.length(0)).turns, 2) << "nothing left to remap";
  EXPECT_EQ(remapped(ShearImages{0, 2, on_grid(-0.02, cell.quantum[0]), 0}, 0.03).turns, -1);
}

// The mean flow and SLLOD's exact decay for an L with a shear component: L x, and exp(-L tau) u
// against Eigen's matrix exponential (Pade with scaling and squaring), with equal and with
// different diagonal rates on the shear and gradient axes.
TEST(CellMotion, ShearedMeanFlowAndDecayAreLxAndTheExponential) {
  for (const Vec3& rate : {Vec3(0.0, 0.0, 0.0), Vec3(-3.0, 1.0, 2.0), Vec3(2.0, 0.5, 2.0)}) {
    Mat3 l = rate.asDiagonal();
    l(0, 2) = 40.0;
    CellShearControl c{{0, 2}, 40.0};
    const MeanFlow f = mean_flow(l, c);
    const Vec3 x(0.01, -0.02, 0.03), u(0.3, -0.1, 0.7);
    EXPECT_LT((f.of(x) - l * x).cwiseAbs().maxCoeff(), 1e-15);
    const double tau = 2e-3;
    const Mat3 e = (-tau * l).exp();
    EXPECT_LT((flow_decay(f, tau)(u) - e * u).cwiseAbs().maxCoeff(), 1e-15) << rate.transpose();
    EXPECT_GT(std::abs(flow_decay(f, tau)(u)[0] - std::exp(-tau * rate[0]) * u[0]), 1e-3) << "the shear acts";
  }
  // Without shear: the diagonal alone, the bits of e^(-L_dd tau) u_d.
  const MeanFlow diagonal = mean_flow(Vec3(-3.0, 1.0, 2.0).asDiagonal().toDenseMatrix(), CellShearControl{});
  const Vec3 u(0.3, -0.1, 0.7);
  EXPECT_EQ(flow_decay(diagonal, 1e-3)(u),
            Vec3((-1e-3 * Vec3(-3.0, 1.0, 2.0)).array().exp().matrix()).cwiseProduct(u));
}
