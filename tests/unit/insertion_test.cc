// Insertion during the run, the plain part (dem/scene/insertion.h, docs/insertion.md): the
// candidate placement overlaps nothing, stays in its inlet and is deterministic; the pour's
// plan follows the gradation and shapes; the rate gives the counts due; bad settings are
// refused naming the entry.
#include <gtest/gtest.h>

#include <functional>
#include <numbers>
#include <random>
#include <string>

#include "dem/core/error.h"
#include "dem/scene/insertion.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// Whether any two of the spheres overlap, or any of `placed` overlaps an obstacle.
bool any_overlap(const std::vector<Vec3>& placed, const std::vector<double>& radii,
                 const std::vector<BoundingSphere>& obstacles) {
  for (std::size_t i = 0; i < placed.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if ((placed[i] - placed[j]).norm() < radii[i] + radii[j]) return true;
    for (const BoundingSphere& o : obstacles)
      if ((placed[i] - o.x).norm() < radii[i] + o.radius) return true;
  }
  return false;
}

SceneConfig pour_scene() {
  SceneConfig s;
  s.particles.count = 0;
  s.particles.radius = 1e-3;
  s.container.lx = s.container.ly = 0.02;
  s.time_step = 1e-5;
  s.end_time = 0.5;
  s.insertion.count = 300;
  s.insertion.rate = 2000.0;
  s.insertion.interval = 0.01;
  s.insertion.inlet_lo = Vec3(0.001, 0.001, 0.03);
  s.insertion.inlet_hi = Vec3(0.019, 0.019, 0.04);
  return s;
}

// The message of the error `scene` is refused with (empty when accepted).
std::string refusal(const SceneConfig& s) {
  try {
    validate_insertion(s);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(Insertion, PlacedGrainsOverlapNothingAndStayInTheInlet) {
  const Box inlet{Vec3(0.0, 0.0, 0.1), Vec3(0.02, 0.015, 0.12)};
  // Obstacles in and around the inlet: grains below its floor reach into it, one in its middle.
  std::vector<BoundingSphere> obstacles;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 40; ++k)
    obstacles.push_back({Vec3(0.02 * u(rng), 0.015 * u(rng), 0.1 + 0.002 * (u(rng) - 0.5)), 1.2e-3});
  obstacles.push_back({Vec3(0.01, 0.0075, 0.11), 2e-3});
  std::vector<double> radii;
  for (int k = 0; k < 60; ++k) radii.push_back(0.6e-3 + 0.6e-3 * u(rng));
  const std::vector<Vec3> x = place_in_inlet(inlet, radii, obstacles, 42);
  ASSERT_EQ(x.size(), radii.size()) << "a sparse inlet takes the whole batch";
  EXPECT_FALSE(any_overlap(x, radii, obstacles));
  for (std::size_t k = 0; k < x.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      EXPECT_GE(x[k][d] - radii[k], inlet.lo[d]) << "grain " << k;
      EXPECT_LE(x[k][d] + radii[k], inlet.hi[d]) << "grain " << k;
    }
}

TEST(Insertion, PlacementIsDeterministicAndDependsOnTheSeed) {
  const Box inlet{Vec3(0.0, 0.0, 0.0), Vec3(0.01, 0.01, 0.01)};
  const std::vector<double> radii(30, 0.7e-3);
  const std::vector<BoundingSphere> obstacles = {{Vec3(0.005, 0.005, 0.0), 1.5e-3}};
  const std::vector<Vec3> a = place_in_inlet(inlet, radii, obstacles, 1234);
  const std::vector<Vec3> b = place_in_inlet(inlet, radii, obstacles, 1234);
  const std::vector<Vec3> c = place_in_inlet(inlet, radii, obstacles, 1235);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(a[k][d], b[k][d]);  // bit for bit
  ASSERT_FALSE(c.empty());
  EXPECT_NE(a[0][0], c[0][0]);
}

TEST(Insertion, AFullInletPlacesAPrefixAndABlockedOneNothing) {
  // Far more grains than random sequential addition can fit: a prefix goes in, still without
  // overlap, and the rest wait.
  const Box inlet{Vec3(0.0, 0.0, 0.0), Vec3(0.006, 0.006, 0.006)};
  const std::vector<double> radii(200, 1e-3);
  const std::vector<Vec3> x = place_in_inlet(inlet, radii, {}, 3);
  EXPECT_GT(x.size(), 3u);
  EXPECT_LT(x.size(), radii.size());
  EXPECT_FALSE(any_overlap(x, std::vector<double>(x.size(), 1e-3), {}));
  // An obstacle covering the inlet: nothing goes in.
  const std::vector<BoundingSphere> cover = {{Vec3(0.003, 0.003, 0.003), 0.01}};
  EXPECT_TRUE(place_in_inlet(inlet, radii, cover, 3).empty());
  // A grain larger than the inlet: nothing either.
  EXPECT_TRUE(place_in_inlet(inlet, std::vector<double>{0.004}, {}, 3).empty());
}

TEST(Insertion, PlanFollowsTheGradationAndShapesAndIsReproducible) {
  SceneConfig s = pour_scene();
  s.particles.gradation = {{0.8e-3, 0.0}, {1.2e-3, 1.0}};
  s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 2.0), ellipsoid_grain(0.8, 0.6, 1.0)};
  const PourPlan a = plan_pour(s), b = plan_pour(s);
  ASSERT_EQ(a.radius.size(), 300u);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.shape, b.shape);
  long spheres = 0;
  for (std::size_t k = 0; k < a.radius.size(); ++k) {
    EXPECT_GE(a.radius[k], 0.8e-3);
    EXPECT_LE(a.radius[k], 1.2e-3);
    spheres += a.shape[k] == 0;
  }
  EXPECT_EQ(spheres, 200);  // number fractions 2 : 1, largest remainder
  // The cumulative mass: each grain's mass from its radius and shape.
  const std::size_t k = 5;
  const double r = a.radius[k];
  const GrainShape g = s.particles.shapes[static_cast<std::size_t>(a.shape[k])];
  const double b_c = g.is_sphere() ? 1.0 : g.ratios[0] * g.ratios[1];  // b/a c/a
  const double m = s.particles.material.density * 4.0 / 3.0 * std::numbers::pi * r * r * r * b_c;
  EXPECT_NEAR(a.cumulative_mass[k] - a.cumulative_mass[k - 1], m, 1e-12 * m);
  // The fill's stream is not the pour's: adding a pour leaves the initial grains alone, and
  // another seed gives another pour.
  s.fill.seed += 1;
  EXPECT_NE(plan_pour(s).radius, a.radius);
}

TEST(Insertion, GrainsDueFollowTheRateUpToTheCount) {
  SceneConfig s = pour_scene();
  const PourPlan plan = plan_pour(s);
  // 2000 grains/s, batches every 0.01 s: 20 per batch, 300 in all after 15 batches.
  EXPECT_EQ(grains_due(s.insertion, plan, 0), 20);
  EXPECT_EQ(grains_due(s.insertion, plan, 4), 100);
  EXPECT_EQ(grains_due(s.insertion, plan, 14), 300);
  EXPECT_EQ(grains_due(s.insertion, plan, 100), 300);
  // A mass rate of 20 grains' mass per interval gives the same counts for equal grains.
  const double m = plan.cumulative_mass[0];
  s.insertion.rate = 0.0;
  s.insertion.mass_rate = 20.0 * m / s.insertion.interval;
  EXPECT_EQ(grains_due(s.insertion, plan, 0), 20);
  EXPECT_EQ(grains_due(s.insertion, plan, 9), 200);
  EXPECT_EQ(grains_due(s.insertion, plan, 20), 300);
}

TEST(Insertion, InletLoadCountsTheBatchesStillFallingThroughTheInlet) {
  SceneConfig s = pour_scene();
  // 20 spheres of 1 mm per batch in an inlet of 18 x 18 x 10 mm.
  const double batch = 20.0 * 4.0 / 3.0 * std::numbers::pi * 1e-9 / (0.018 * 0.018 * 0.01);
  InletLoad load = inlet_load(s);
  EXPECT_EQ(load.grains_per_batch, 20);
  EXPECT_NEAR(load.batch, batch, 1e-12 * batch);
  // From rest a grain falls 1 cm in sqrt(2 h / g) = 0.045 s: the batch placed then and the four
  // before it lie in the inlet together.
  EXPECT_DOUBLE_EQ(load.held, 5.0 * load.batch);
  // At 1 m/s down it is out in 9.6 ms, before the next batch.
  s.insertion.velocity = Vec3(0.0, 0.0, -1.0);
  EXPECT_DOUBLE_EQ(inlet_load(s).held, load.batch);
}

TEST(Insertion, BadSettingsAreRefusedNamingTheEntry) {
  EXPECT_EQ(refusal(pour_scene()), "");
  auto refused = [](const std::function<void(SceneConfig&)>& change, const std::string& words) {
    SceneConfig s = pour_scene();
    change(s);
    const std::string m = refusal(s);
    EXPECT_NE(m.find(words), std::string::npos) << "message: '" << m << "', expected '" << words << "'";
  };
  refused([](SceneConfig& s) { s.insertion.rate = 0.0; }, "Insertion/rate = 0");
  refused([](SceneConfig& s) { s.insertion.mass_rate = 1.0; }, "are both set");
  refused([](SceneConfig& s) { s.insertion.count = -3; }, "Insertion/count = -3");
  refused([](SceneConfig& s) { s.insertion.inlet_hi.x() = 0.03; }, "outside the container along x");
  refused([](SceneConfig& s) { s.insertion.inlet_lo.z() = -0.01; }, "outside the container along z");
  refused([](SceneConfig& s) { s.insertion.inlet_hi.z() = 0.0301; }, "too small for one grain");
  refused([](SceneConfig& s) { s.insertion.inlet_hi.y() = 0.0; }, "is empty along y");
  refused([](SceneConfig& s) { s.insertion.interval = 1e-6; }, "Insertion/interval");
  refused([](SceneConfig& s) { s.insertion.start_time = 0.6; }, "Insertion/start time");
  refused([](SceneConfig& s) { s.insertion.rate = 2e5; }, "enlarge the inlet");
  // The gate shortens the room along x.
  refused(
      [](SceneConfig& s) {
        s.container.gate_x = 0.01;
        s.container.gate_open_time = 0.1;
      },
      "behind the gate");
}
