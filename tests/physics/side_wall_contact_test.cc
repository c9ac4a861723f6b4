// The side-wall contacts a study bins into its wall shear against height
// (coupling::side_wall_contacts, docs/study.md "Wall shear against height"): a sphere thrown
// down against a side wall with friction slides along it, so the wall's force on the grain
// pushes it off the wall (+x for wall_x_min) and, by Coulomb friction, upward (the wall carries
// weight: a positive shear); the floor's contact is not a side wall's.
#include <gtest/gtest.h>

#include <cmath>

#include "../common/scenes.h"
#include "coupling/run/run_result.h"
#include "dem/engine/simulation.h"

using namespace upgrain;
using namespace upgrain::dem;

TEST(SideWallContacts, AGrainSlidingDownAWallIsHeldUpByIt) {
  SceneConfig s = test::bare_scene(1e-6);
  s.effects.gravity = true;
  s.effects.friction = true;
  s.effects.wall_friction = true;
  s.effects.rotation = true;
  s.container.lx = s.container.ly = 0.1;
  const double r = 5e-3;
  ParticleStore p;
  // Just off the wall, moving into it and down; a second one resting on the floor.
  p.add_sphere(0, r, 2650.0, Vec3(r + 1e-5, 0.05, 0.05), Vec3(-0.2, 0.0, -0.3), Vec3::Zero());
  p.add_sphere(1, r, 2650.0, Vec3(0.05, 0.05, r), Vec3::Zero(), Vec3::Zero());
  const std::vector<PlaneWall> walls = {{"floor", Vec3::Zero(), Vec3(0, 0, 1), 0.5},
                                        {"wall_x_min", Vec3::Zero(), Vec3(1, 0, 0), 0.5}};
  Simulation sim(s, p, walls);
  sim.run(200);  // 0.2 ms: in contact with the wall after 0.05 ms
  sim.request_contacts();
  sim.step();
  const std::vector<coupling::SideWallContact> c = coupling::side_wall_contacts(sim);
  ASSERT_EQ(c.size(), 1u) << "the floor's contact is not a side wall's";
  EXPECT_EQ(c[0].wall, 1);
  EXPECT_GT(c[0].force_on_grain.x(), 0.0) << "the wall pushes the grain off";
  EXPECT_GT(c[0].force_on_grain.z(), 0.0) << "friction holds the sliding grain up";
  // Sliding: the friction is at its Coulomb limit.
  EXPECT_NEAR(std::hypot(c[0].force_on_grain.y(), c[0].force_on_grain.z()), 0.5 * c[0].force_on_grain.x(),
              1e-9 * c[0].force_on_grain.x());
  // At the height of the sliding grain (id 0; local indices follow the cells).
  const ParticleStore& now = sim.particles();
  for (int i = 0; i < sim.owned(); ++i)
    if (now.id[i] == 0) {
      EXPECT_NEAR(c[0].z, now.x[i].z(), 1e-12);
    }
}
