// Ellipsoid grains in the particle store and in scenes: mass and
// principal inertia of a solid ellipsoid, the world inertia, mixed sphere-ellipsoid stores,
// reordering, the shape mix of a fill and its random orientations, refusal of bad shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "dem/analysis/bed_state.h"
#include "dem/core/error.h"
#include "dem/core/particle_store.h"
#include "dem/scene/fill.h"
#include "dem/scene/grain_shape.h"

using namespace upgrain;
using namespace upgrain::dem;

TEST(EllipsoidGrain, MassInertiaAndRotationalEnergy) {
  ParticleStore p;
  const Vec3 ax(3e-3, 2e-3, 1e-3);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.1, Vec3(0.2, 1, -0.4).normalized()));
  p.add_ellipsoid(7, {ax, 2000, q}, {Vec3(1, 2, 3), Vec3::Zero(), Vec3(4, -5, 6)});
  const double m = 2000 * 4.0 / 3.0 * std::numbers::pi * 6e-9;
  EXPECT_NEAR(p.mass(0), m, 1e-15 * m);
  EXPECT_DOUBLE_EQ(p.radius[0], 3e-3);  // bounding radius
  EXPECT_NEAR(p.volume(0), 4.0 / 3.0 * std::numbers::pi * 6e-9, 1e-22);
  // Principal moments m (b^2 + c^2) / 5 etc. are the eigenvalues of the world inertia, along
  // the rotated body axes.
  const Mat3 i_world = p.inertia_world(0);
  const Vec3 j = m / 5.0 * Vec3(5e-6, 10e-6, 13e-6);
  for (int k = 0; k < 3; ++k) {
    const Vec3 axis = q * Vec3::Unit(k);
    EXPECT_LE((i_world * axis - j[k] * axis).norm(), 1e-12 * j[k]) << "axis " << k;
  }
  EXPECT_LE((i_world - i_world.transpose()).norm(), 1e-15 * i_world.norm());
  const Vec3 w = p.omega[0];
  EXPECT_NEAR(p.rotational_energy(0), 0.5 * w.dot(i_world * w), 1e-13 * p.rotational_energy(0));
  EXPECT_TRUE(p.is_ellipsoid(0));
  EXPECT_DOUBLE_EQ(p.min_semi_axis(0), 1e-3);
}

TEST(EllipsoidGrain, MixedStoresAndReorderingKeepShapes) {
  ParticleStore p;
  p.add_sphere(0, 2e-3, 2650, Vec3::Zero(), Vec3::Zero(), Vec3::Zero());
  EXPECT_FALSE(p.has_shapes());
  p.add_ellipsoid(1, {Vec3(3e-3, 2e-3, 1e-3), 2650, Eigen::Quaterniond::Identity()},
                  {Vec3::Ones(), Vec3::Zero(), Vec3::Zero()});
  p.add_sphere(2, 1e-3, 2650, Vec3::Zero(), Vec3::Zero(), Vec3::Zero());
  ASSERT_TRUE(p.has_shapes());
  ASSERT_EQ(p.semi_axes.size(), 3u);
  EXPECT_FALSE(p.is_ellipsoid(0));
  EXPECT_TRUE(p.is_ellipsoid(1));
  EXPECT_FALSE(p.is_ellipsoid(2));
  EXPECT_EQ(p.semi_axes[0], Vec3::Constant(2e-3));
  EXPECT_NEAR(p.inertia_body[0].x(), 0.4 * p.mass(0) * 4e-6, 1e-20);
  EXPECT_NEAR(p.inertia_world(2)(0, 0), 0.4 * p.mass(2) * 1e-6, 1e-22);
  p.permute({2, 0, 1});
  EXPECT_EQ(p.id[2], 1);
  EXPECT_TRUE(p.is_ellipsoid(2));
  EXPECT_EQ(p.semi_axes[2], Vec3(3e-3, 2e-3, 1e-3));
  EXPECT_EQ(p.semi_axes[0], Vec3::Constant(1e-3));
}

TEST(EllipsoidGrain, RefusesSemiAxesOutOfOrder) {
  ParticleStore p;
  try {
    p.add_ellipsoid(42, {Vec3(1e-3, 2e-3, 1e-3), 2650, Eigen::Quaterniond::Identity()},
                    {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
    FAIL() << "accepted b > a";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("particle 42"), std::string::npos) << e.what();
  }
}

TEST(GrainShapes, FractionsOrientationsAndValidation) {
  std::mt19937_64 rng(5);
  const std::vector<GrainShape> mix = {ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(0.8, 0.6, 1.0),
                                       ellipsoid_grain(0.6, 0.4, 2.0)};
  const std::vector<int> shape = assign_shapes(mix, 1001, rng);
  long count[3] = {0, 0, 0};
  for (int k : shape) ++count[k];
  EXPECT_EQ(count[0] + count[1] + count[2], 1001);
  EXPECT_LE(std::abs(count[0] - 250.25), 1.0);
  EXPECT_LE(std::abs(count[2] - 500.5), 1.0);
  // Uniform over SO(3): unit quaternions whose rotated axis averages to zero.
  Vec3 mean = Vec3::Zero();
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const Eigen::Quaterniond q = random_orientation(rng);
    ASSERT_NEAR(q.norm(), 1.0, 1e-14);
    mean += q * Vec3::UnitZ();
  }
  EXPECT_LT((mean / n).norm(), 4.0 / std::sqrt(static_cast<double>(n)));
  EXPECT_THROW(validate_shapes({ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(0.4, 0.6, 1.0)}), Error);
  EXPECT_THROW(validate_shapes({ellipsoid_grain(0.8, 0.6, 0.0)}), Error);
  EXPECT_NO_THROW(validate_shapes(mix));
  try {
    validate_shapes({ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(0.4, 0.6, 1.0)});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("shape 2"), std::string::npos) << e.what();
  }
}

// A scene's mix goes through the shape table: the text reads back as written, a name picks the
// row, equal dimensions are the sphere, and each row's scales and stored ratios are its own.
TEST(GrainShapes, TheMixIsReadWrittenAndScaledThroughTheShapeTable) {
  const auto text = [](const GrainShape& g) {
    return format_grain_shape(g, [](double v) {
      std::ostringstream s;
      s << v;
      return s.str();
    });
  };
  const GrainShape e = read_grain_shape(" 10:8:6@2");
  EXPECT_EQ(e.kind, ShapeKind::ellipsoid);
  EXPECT_DOUBLE_EQ(e.ratios[0], 0.8);
  EXPECT_DOUBLE_EQ(e.ratios[1], 0.6);
  EXPECT_EQ(e.number_fraction, 2.0);
  EXPECT_EQ(text(e), "1:0.8:0.6");
  EXPECT_EQ(read_grain_shape("ellipsoid 1:0.8:0.6").ratios, e.ratios);
  EXPECT_TRUE(read_grain_shape("2:2:2").is_sphere());
  EXPECT_TRUE(read_grain_shape("sphere 3").is_sphere());
  EXPECT_EQ(text(read_grain_shape("sphere 3")), "1:1:1");
  EXPECT_THROW(read_grain_shape("1:0.8"), Error);
  EXPECT_THROW(read_grain_shape("sphere 1:1"), Error);
  try {
    (void)read_grain_shape("cube 1:1:1");
    ADD_FAILURE() << "an unknown shape was read";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("no shape is named 'cube' (the shapes: sphere, ellipsoid)"),
              std::string::npos)
        << err.what();
  }
  const ShapeScales k = scales(e);
  EXPECT_DOUBLE_EQ(k.thinnest, 0.6);
  EXPECT_DOUBLE_EQ(k.flattest, 0.8 / 0.6);
  EXPECT_DOUBLE_EQ(k.volume, 0.8 * 0.6);
  EXPECT_EQ(scales(GrainShape{}).volume, 1.0);
  EXPECT_EQ(shape_nouns({GrainShape{}, e}), "ellipsoids");
  EXPECT_EQ(shape_nouns({GrainShape{}}), "");
  // add_grain makes the grain of its row; grain_shape_of reads its ratios back.
  ParticleStore p;
  add_grain(p, GrainShape{}, 1, 2e-3, 2500, Eigen::Quaterniond::Identity(),
            {Vec3::Zero(), Vec3::Zero(), Vec3::Zero()});
  add_grain(p, e, 2, 2e-3, 2500, Eigen::Quaterniond::Identity(), {Vec3::Ones(), Vec3::Zero(), Vec3::Zero()});
  ASSERT_TRUE(p.has_shapes());
  EXPECT_EQ(p.kind(0), ShapeKind::sphere);
  EXPECT_EQ(p.kind(1), ShapeKind::ellipsoid);
  EXPECT_EQ(p.semi_axes[1], Vec3(2e-3, 2e-3 * 0.8, 2e-3 * 0.6));
  EXPECT_TRUE(grain_shape_of(p, 0).is_sphere());
  EXPECT_NEAR(grain_shape_of(p, 1).ratios[0], 0.8, 1e-15);
  EXPECT_NEAR(grain_shape_of(p, 1).ratios[1], 0.6, 1e-15);
}

TEST(GrainShapes, AFillPlacesTheSameCentresWhateverTheShapes) {
  SceneConfig s;
  s.particles.count = 200;
  s.particles.gradation = {{1e-3, 0.0}, {2.5e-3, 1.0}};
  s.container.lx = s.container.ly = 0.03;
  const ParticleStore spheres = fill_container(s);
  s.particles.shapes = {ellipsoid_grain(1.0, 1.0, 1.0), ellipsoid_grain(0.8, 0.6, 1.0),
                        ellipsoid_grain(0.8, 0.4, 1.0), ellipsoid_grain(0.6, 0.4, 1.0)};
  const ParticleStore mixed = fill_container(s);
  ASSERT_TRUE(mixed.has_shapes());
  long ellipsoids = 0;
  for (std::size_t i = 0; i < mixed.size(); ++i) {
    EXPECT_EQ(mixed.x[i], spheres.x[i]);
    EXPECT_EQ(mixed.radius[i], spheres.radius[i]);  // the major semi-axis
    EXPECT_DOUBLE_EQ(mixed.semi_axes[i].x(), spheres.radius[i]);
    ellipsoids += mixed.is_ellipsoid(i) ? 1 : 0;
  }
  EXPECT_EQ(ellipsoids, 150);
}

// The bed measures use the ellipsoids themselves, not their bounding spheres: aligned
// 1:0.5:0.5 ellipsoids on a simple cubic lattice have the solid fraction (4/3) pi a b c / h^3
// (a quarter of their bounding spheres'), and a column's top is the highest grain's top.
TEST(GrainShapes, BedSolidFractionAndSurfaceUseTheEllipsoids) {
  const Vec3 ax(2e-3, 1e-3, 1e-3);
  const double h =
      4e-3;  // = a + a along z: the core box (two diameters, 2 h, in from each side) spans 8 cells each way
  ParticleStore p;
  const Eigen::Quaterniond upright(Eigen::AngleAxisd(0.5 * std::numbers::pi, Vec3::UnitY()));  // a along z
  long id = 0;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      for (int k = 0; k < 12; ++k)
        p.add_ellipsoid(id++, {ax, 2650, upright},
                        {Vec3((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h), Vec3::Zero(), Vec3::Zero()});
  BoxContainer box;
  box.lx = box.ly = 12 * h;
  const BedState bed = measure_bed(p, box);
  const double expected = 4.0 / 3.0 * std::numbers::pi * ax.prod() / (h * h * h);
  EXPECT_NEAR(bed.solid_fraction, expected, 0.03 * expected)
      << "bounding spheres would give " << 4 * expected;
  EXPECT_NEAR(bed.surface_height, 11.5 * h + ax.x(), 1e-12);  // the a axis stands upright
}
