// How the DEM cell follows a trial displacement gradient (coupling/femxdem/cell_increment.h): the
// upper-triangular factor of F, the refusal of tilts the cell cannot hold, and the velocity
// gradient that brings the engine's cell (its own update, dem/core/cell_motion.h) to the target.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "coupling/femxdem/cell_increment.h"
#include "dem/core/cell_motion.h"
#include "dem/core/periodic_cell.h"

using namespace upgrain;
using namespace upgrain::coupling;
using dem::Mat3;

// A plane-strain F in x-y (a shear with a rotation and stretches, z stretched too): Q R = F, Q a
// rotation about z, R upper triangular with a positive diagonal and exactly no (x, z) or (y, z)
// tilt, so the one-tilt check passes.
TEST(CellIncrement, PlaneStrainFactorHasTheOneTiltExactly) {
  Mat3 f;
  f << 1.002, 3e-3, 0, -1e-3, 0.997, 0, 0, 0, 1.001;
  const CellFactor c = upper_triangular_factor(f);
  EXPECT_LE((c.rotation * c.stretch - f).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((c.rotation.transpose() * c.rotation - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NEAR(c.rotation.determinant(), 1.0, 1e-15);
  EXPECT_EQ(c.rotation(2, 2), 1.0);
  for (int d = 0; d < 3; ++d) EXPECT_GT(c.stretch(d, d), 0.0);
  EXPECT_EQ(c.stretch(1, 0), 0.0);
  EXPECT_EQ(c.stretch(0, 2), 0.0);
  EXPECT_EQ(c.stretch(1, 2), 0.0);
  EXPECT_GT(std::abs(c.stretch(0, 1)), 1e-3);
  EXPECT_NO_THROW(check_one_tilt(c.stretch));
}

// A 3D F with shears across z: its R has tilts (x, z) and (y, z), which the engine's cell (one
// tilt) cannot hold: refused, naming the component and the plan.
TEST(CellIncrement, TiltsAcrossZAreRefusedByName) {
  Mat3 f = Mat3::Identity();
  f(0, 2) = 1e-3;
  f(1, 2) = 2e-3;
  const CellFactor c = upper_triangular_factor(f);
  try {
    check_one_tilt(c.stretch);
    FAIL() << "a tilt across z was taken";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("R(x, z)"), std::string::npos) << what;
    EXPECT_NE(what.find("triclinic"), std::string::npos) << what;
  }
  EXPECT_THROW((void)upper_triangular_factor(-Mat3::Identity()), std::invalid_argument);
}

// Guo and Zhao's steps: 1e5 a unit strain, at least 2.
TEST(CellIncrement, StepsFollowTheLargestComponent) {
  const RveOptions o;
  Mat3 dh = Mat3::Zero();
  EXPECT_EQ(increment_steps(dh, o), 2);
  dh(1, 0) = -3.2e-4;
  dh(0, 0) = 1e-4;
  EXPECT_EQ(increment_steps(dh, o), 32);
}

// The velocity gradient of an increment, stepped by the engine's own update of the faces and the
// tilt (advanced_cell_box, advanced_offset), takes a sheared cell to the target within the
// position grid's roundings (half a quantum a step each).
TEST(CellIncrement, EnginesUpdateReachesTheTargetCell) {
  dem::PeriodicCell cell =
      dem::make_periodic_cell({dem::Vec3::Zero(), dem::Vec3(0.011, 0.012, 0.010)}, {true, true, true}, 2.0);
  cell.shear = dem::ShearImages{kTiltShear, kTiltGradient, 2e-5, 0};
  cell.shear.offset = dem::on_grid(cell.shear.offset, cell.quantum[0]);
  const Mat3 from = dem::cell_matrix(cell);
  Mat3 to = from;
  to(0, 0) *= 0.9996;
  to(1, 1) *= 1.0003;
  to(2, 2) *= 0.9999;
  to(0, 1) = -3e-6;
  const double dt = 5e-6;
  const long n = 40;
  const Mat3 l = increment_velocity_gradient(from, to, n, dt);
  EXPECT_EQ(l(1, 0), 0.0);
  EXPECT_EQ(l(0, 2), 0.0);
  for (long k = 0; k < n; ++k) {
    const dem::Box next = dem::advanced_cell_box(cell, l, dt);
    const double offset = dem::advanced_offset(cell, l, dt);
    cell.box = next;
    cell.shear.offset = offset;
  }
  const Mat3 reached = dem::cell_matrix(cell);
  const double q = cell.quantum.maxCoeff();
  EXPECT_LE((reached - to).cwiseAbs().maxCoeff(), static_cast<double>(n) * q) << reached - to;
  EXPECT_GT((from - to).cwiseAbs().maxCoeff(), 1e6 * static_cast<double>(n) * q) << "the cell moved";
}
