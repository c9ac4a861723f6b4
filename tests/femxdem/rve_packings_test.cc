// Which prepared DEM cell each Gauss point copies (coupling/femxdem/rve_packings.h,
// docs/femxdem.md, "Point-to-point variability").
#include "coupling/femxdem/rve_packings.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/femxdem/rve_point.h"
#include "dem/core/error.h"
#include "tests/femxdem/small_cell.h"

namespace upgrain::coupling {
namespace {

// The Gauss points of a 2 x 4 Q1 mesh by their places (deal.II's coarse cell ids).
std::vector<fem::PointPlace> mesh_places() {
  std::vector<fem::PointPlace> places;
  for (int cell = 0; cell < 8; ++cell)
    for (unsigned q = 0; q < 4; ++q) places.push_back({std::to_string(cell) + "_0:", q, {}});
  return places;
}

// FNV-1a over the cell's id, '/', and the index's four bytes, low first: the reference computed
// apart (Python: h = 14695981039346656037; h = ((h ^ byte) * 1099511628211) mod 2^64).
TEST(RvePackings, PlaceHashIsFnv1aOfThePlace) {
  EXPECT_EQ(place_hash({"3_0:", 2, {}}), 11893017478530284788ull);
  EXPECT_NE(place_hash({"3_0:", 2, {}}), place_hash({"3_0:", 1, {}}));
  EXPECT_EQ(place_hash({"3_0:", 2, {0.1, 0.2, 0.0}}), place_hash({"3_0:", 2, {}}));  // the place, not where
}

TEST(RvePackings, OnePackingIsCopiedToEveryPoint) {
  const RveOptions o = small_cell();
  RvePackings packings(sphere_scene(), o, 1);
  const auto first = packings.first();
  for (const fem::PointPlace& p : mesh_places()) {
    EXPECT_EQ(packings.seed_of(p), o.seed);
    EXPECT_EQ(packings.for_point(p), first);
  }
  EXPECT_EQ(packings.prepared(), 1u);
}

// Three packings: every point's seed is one of the three, each used, the same place always the
// same prepared cell; and distinct packings are distinct cells at the same pressure.
TEST(RvePackings, PointsPickAmongThePackingsByPlace) {
  const RveOptions o = small_cell();
  RvePackings packings(sphere_scene(), o, 3);
  std::set<std::uint64_t> seeds;
  for (const fem::PointPlace& p : mesh_places()) {
    const std::uint64_t s = packings.seed_of(p);
    EXPECT_GE(s, o.seed);
    EXPECT_LT(s, o.seed + 3);
    seeds.insert(s);
  }
  EXPECT_EQ(seeds.size(), 3u);
  const fem::PointPlace a = mesh_places()[0];
  const fem::PointPlace b = [&] {
    for (const fem::PointPlace& p : mesh_places())
      if (packings.seed_of(p) != packings.seed_of(a)) return p;
    return a;
  }();
  const auto ta = packings.for_point(a), tb = packings.for_point(b);
  EXPECT_EQ(packings.for_point(a), ta);
  EXPECT_NE(ta, tb);
  EXPECT_EQ(packings.prepared(), 2u);
  EXPECT_NE(ta->state.particles.x[0], tb->state.particles.x[0]);
  for (const auto& t : {ta, tb})
    EXPECT_NEAR(-fem::mandel::trace(t->stress) / 3.0, o.mean_stress, 0.02 * o.mean_stress);
}

// Every point its own: the 32 places give 32 seeds.
TEST(RvePackings, EveryPointItsOwnSeed) {
  RvePackings packings(sphere_scene(), small_cell(), 0);
  std::set<std::uint64_t> seeds;
  for (const fem::PointPlace& p : mesh_places()) seeds.insert(packings.seed_of(p));
  EXPECT_EQ(seeds.size(), 32u);
  EXPECT_EQ(packings.prepared(), 0u);  // nothing prepared until a point asks
}

// A cell that arrives with its bytes (a restart, a move to another rank) is not prepared again: its
// packing's frame comes from the fill alone and the rest from the bytes, and it answers the next
// trial with the same bits as the cell it was saved from, its measures the same; the frame has the
// prepared packing's grains, cell size and seed.
TEST(RvePackings, ALoadedCellIsNotPreparedAgain) {
  const RveOptions o = small_cell();
  const fem::PointPlace place{"5_0:", 2, {}};
  const auto source = [&](RvePackings& packings) {
    return RveSource{[&packings, place] { return packings.for_point(place); },
                     [&packings, place] { return packings.frame_for_point(place); }};
  };
  fem::Mat3x3 h1 = fem::Mat3x3::Zero(), h2 = fem::Mat3x3::Zero();
  h1(0, 0) = -2e-4;
  h1(0, 1) = 1e-4;
  h2 = 2.0 * h1;
  h2(1, 1) = 1e-4;

  RvePackings here(sphere_scene(), o, 0);
  RveCell saved(source(here), o);
  EXPECT_THROW((void)saved.measures(), std::logic_error) << "neither started nor loaded";
  saved.start();
  (void)saved.respond(h1);
  saved.commit();
  const std::vector<char> bytes = saved.save();
  const fem::PointResponse expected = saved.respond(h2);

  RvePackings there(sphere_scene(), o, 0);
  RveCell loaded(source(there), o);
  loaded.load(bytes);
  const fem::PointResponse got = loaded.respond(h2);
  EXPECT_EQ(there.prepared(), 0u);
  EXPECT_TRUE(got.stress == expected.stress);
  EXPECT_TRUE(got.tangent == expected.tangent);
  EXPECT_EQ(got.cost, expected.cost);
  loaded.commit();
  saved.commit();
  const auto a = saved.measures(), b = loaded.measures();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].value, b[k].value) << a[k].name;
  EXPECT_EQ(saved.save(), loaded.save());

  std::vector<char> older = bytes;
  older[0] ^= 1;  // another layout's first word
  RveCell refused(source(there), o);
  EXPECT_THROW(refused.load(older), Error);

  const auto frame = there.frame_for_point(place);
  const auto prepared = here.for_point(place);
  EXPECT_EQ(frame->grains, prepared->grains);
  EXPECT_EQ(frame->engine.summation, prepared->engine.summation);
  EXPECT_EQ(frame->engine.box.has_value(), prepared->engine.box.has_value());
  EXPECT_EQ(frame->scene.container.lx, prepared->scene.container.lx);
  EXPECT_EQ(frame->scene.fill.seed, prepared->scene.fill.seed);
}

}  // namespace
}  // namespace upgrain::coupling
