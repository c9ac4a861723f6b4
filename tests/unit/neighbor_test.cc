// The Verlet list finds exactly the pairs a brute-force search finds, and carries each
// tangential spring over a rebuild by the pair of global ids, whatever the new order.
#include "dem/neighbor/verlet_list.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

using namespace upgrain::dem;

namespace {
ParticleStore random_particles(int n, double box, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, box), ur(0.5e-3, 1.5e-3);
  ParticleStore p;
  for (int i = 0; i < n; ++i)
    p.add_sphere(1000 + 7 * i, ur(rng), 2650, Vec3(u(rng), u(rng), u(rng)), Vec3::Zero(), Vec3::Zero());
  return p;
}
std::set<std::pair<GlobalId, GlobalId>> pairs_of(const VerletList& l, const ParticleStore& p) {
  std::set<std::pair<GlobalId, GlobalId>> s;
  for (std::size_t i = 0; i + 1 < l.offsets().size(); ++i)
    for (int k = l.offsets()[i]; k < l.offsets()[i + 1]; ++k) {
      const GlobalId a = p.id[i], b = p.id[l.partners()[k]];
      s.emplace(std::min(a, b), std::max(a, b));
    }
  return s;
}
}  // namespace

TEST(VerletList, MatchesBruteForce) {
  const double box = 0.02, skin = 0.4e-3;
  ParticleStore p = random_particles(1500, box, 7);
  VerletList list(p.max_radius(), skin, true);
  list.rebuild(p);
  std::set<std::pair<GlobalId, GlobalId>> brute;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double cut = p.radius[i] + p.radius[j] + skin;
      if ((p.x[i] - p.x[j]).squaredNorm() < cut * cut)
        brute.emplace(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]));
    }
  EXPECT_FALSE(brute.empty());
  EXPECT_EQ(pairs_of(list, p), brute);
}

TEST(VerletList, PositionsOutsideTheGridAreStillFound) {
  ParticleStore p;
  // Two touching grains far above the grid: both clamp into the top cells.
  p.add_sphere(1, 1e-3, 2650, Vec3(0.005, 0.005, 0.5), Vec3::Zero(), Vec3::Zero());
  p.add_sphere(2, 1e-3, 2650, Vec3(0.005, 0.005, 0.5019), Vec3::Zero(), Vec3::Zero());
  VerletList list(1e-3, 1e-4, false);
  list.rebuild(p);
  EXPECT_EQ(list.num_pairs(), 1u);
}

TEST(VerletList, RebuildCarriesSpringsByGlobalId) {
  const double box = 0.01, skin = 0.3e-3;
  ParticleStore p = random_particles(400, box, 11);
  VerletList list(p.max_radius(), skin, true);
  list.rebuild(p);
  // Give every pair a spring that encodes its ids, oriented as the force on local i.
  std::map<std::pair<GlobalId, GlobalId>, Vec3> expected;  // force on the smaller id
  for (std::size_t i = 0; i + 1 < list.offsets().size(); ++i)
    for (int k = list.offsets()[i]; k < list.offsets()[i + 1]; ++k) {
      const GlobalId a = p.id[i], b = p.id[list.partners()[k]];
      const Vec3 s(static_cast<double>(a), static_cast<double>(b), 1.0);
      list.springs()[k] = TangentialSpring{s, 1.0};
      expected[{std::min(a, b), std::max(a, b)}] = a < b ? s : Vec3(-s);
    }
  // Move the particles a little (keeping all pairs inside the cut-off) and rebuild:
  // the sort by cell reorders them.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e-5, 1e-5);
  for (auto& x : p.x) x += Vec3(u(rng), u(rng), u(rng));
  list.rebuild(p);
  int checked = 0;
  for (std::size_t i = 0; i + 1 < list.offsets().size(); ++i)
    for (int k = list.offsets()[i]; k < list.offsets()[i + 1]; ++k) {
      const GlobalId a = p.id[i], b = p.id[list.partners()[k]];
      auto it = expected.find({std::min(a, b), std::max(a, b)});
      if (it == expected.end()) continue;
      const Vec3 on_i = a < b ? it->second : Vec3(-it->second);
      EXPECT_EQ(list.springs()[k].force, on_i);
      ++checked;
    }
  EXPECT_GT(checked, 100);
}

TEST(VerletList, NeedsRebuildAfterHalfSkin) {
  ParticleStore p = random_particles(10, 0.01, 5);
  VerletList list(p.max_radius(), 1e-4, false);
  list.rebuild(p);
  EXPECT_FALSE(list.needs_rebuild(p));
  p.x[3].x() += 0.49e-4;
  EXPECT_FALSE(list.needs_rebuild(p));
  p.x[3].x() += 0.02e-4;
  EXPECT_TRUE(list.needs_rebuild(p));
}
