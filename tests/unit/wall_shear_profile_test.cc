// The side walls' shear against height (coupling/studies/continuum/wall_shear_profile.h, docs/study.md "Wall
// shear against height"):
//  - the DEM's binning: each contact's vertical force on its grain in the level of its point
//    (points beyond the grid in the end levels), over the perimeter times the level height, so
//    that the levels sum to the walls' upward force;
//  - Janssen's: summed over the levels, tau_k P dz is the share of the weight the walls carry,
//    1 - p(H) / (rho g H) (the slab equilibrium integrated over the column), at any level count;
//  - a string for a JSON file keeps quotes, backslashes and control characters readable.
#include <gtest/gtest.h>

#include <numeric>

#include "coupling/studies/continuum/wall_shear_profile.h"
#include "dem/files/json_number.h"

using namespace upgrain;
using namespace upgrain::coupling;

TEST(WallShearProfile, DemContactsAreBinnedByTheirPointsHeight) {
  const Levels levels{0.0, 0.01, 3};
  const double perimeter = 0.2;
  const std::vector<SideWallContact> contacts = {
      {1, 0.005, dem::Vec3(0.3, 0.0, 0.02)},    // level 0
      {2, 0.015, dem::Vec3(-0.3, 0.1, 0.04)},   // level 1
      {3, 0.0151, dem::Vec3(0.0, 0.2, -0.01)},  // level 1, pulling down
      {4, 0.035, dem::Vec3(0.0, -0.2, 0.03)},   // above the top: level 2
      {1, -0.001, dem::Vec3(0.1, 0.0, 0.01)},   // below the floor: level 0
  };
  const std::vector<double> tau = dem_wall_shear(contacts, levels, perimeter);
  ASSERT_EQ(tau.size(), 3u);
  const double area = perimeter * levels.dz;
  EXPECT_DOUBLE_EQ(tau[0], (0.02 + 0.01) / area);
  EXPECT_DOUBLE_EQ(tau[1], (0.04 - 0.01) / area);
  EXPECT_DOUBLE_EQ(tau[2], 0.03 / area);
  // The levels carry what the contacts carry.
  EXPECT_NEAR(std::accumulate(tau.begin(), tau.end(), 0.0) * area, 0.09, 1e-15);
  EXPECT_EQ(dem_wall_shear({}, levels, perimeter), std::vector<double>(3, 0.0));
}

TEST(WallShearProfile, JanssenLevelsSumToTheWallsShareOfTheWeight) {
  // A 2 cm x 3 cm silo 5 cm deep, mu_w 0.5 on the x walls and 0.3 on the y walls, K = 0.6.
  const double lx = 0.02, ly = 0.03, h = 0.05, rho_g = 1500.0 * 9.81;
  fem::JanssenColumn j;
  j.unit_weight = rho_g;
  j.area = lx * ly;
  j.friction_perimeter = 2 * 0.5 * ly + 2 * 0.3 * lx;
  j.lateral_ratio = 0.6;
  j.height = h;
  const double perimeter = 2 * (lx + ly);
  for (int n : {1, 4, 13}) {
    SCOPED_TRACE(n);
    const Levels levels{0.0, h / n, n};
    const std::vector<double> tau = janssen_wall_shear(j, levels, perimeter);
    const double carried = std::accumulate(tau.begin(), tau.end(), 0.0) * perimeter * levels.dz;
    EXPECT_NEAR(carried, j.wall_share() * rho_g * j.area * h, 1e-12 * rho_g * j.area * h);
    // The shear grows with depth, as the pressure does.
    for (int k = 1; k < n; ++k) EXPECT_LT(tau[k], tau[k - 1]);
    EXPECT_GT(tau.back(), 0.0);
  }
}

TEST(JsonString, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(dem::io::json_string("plain"), "\"plain\"");
  EXPECT_EQ(dem::io::json_string("a \"b\" c\\d"), "\"a \\\"b\\\" c\\\\d\"");
  EXPECT_EQ(dem::io::json_string(std::string("x\ny\t\x01")), "\"x\\u000ay\\u0009\\u0001\"");
}
