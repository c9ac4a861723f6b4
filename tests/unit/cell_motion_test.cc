// The deforming cell's kernel with numbers (dem/core/cell_motion.h, docs/periodic.md).
#include "dem/core/cell_motion.h"

#include <gtest/gtest.h>

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
