// The Verlet lists find exactly the pairs a brute-force search finds, in both orders, and the
// contact-history store carries each tangential spring over a rebuild by the pair of global
// ids, whatever the new order.
#include "dem/neighbor/verlet_list.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

#include "dem/core/contact_history.h"

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

// Calls f(k, i, j) for every slot k of pair (i, j).
template <class F>
void for_slots(const PairList& l, F f) {
  for (std::size_t r = 0; r < l.num_rows(); ++r)
    for (int k = l.row_start[r]; k < l.row_start[r + 1]; ++k) f(k, l.row_particle[r], l.partner[k]);
}

std::set<std::pair<GlobalId, GlobalId>> pairs_of(const VerletList& l, const ParticleStore& p) {
  std::set<std::pair<GlobalId, GlobalId>> s;
  for_slots(l.pairs(), [&](int, int i, int j) {
    const GlobalId a = p.id[i], b = p.id[j];
    s.emplace(std::min(a, b), std::max(a, b));
  });
  return s;
}

const PairOrder kOrders[] = {PairOrder::local, PairOrder::global_id};
}  // namespace

TEST(VerletList, MatchesBruteForce) {
  const double box = 0.02, skin = 0.4e-3;
  ParticleStore p = random_particles(1500, box, 7);
  std::set<std::pair<GlobalId, GlobalId>> brute;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double cut = p.radius[i] + p.radius[j] + skin;
      if ((p.x[i] - p.x[j]).squaredNorm() < cut * cut)
        brute.emplace(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]));
    }
  EXPECT_FALSE(brute.empty());
  for (const PairOrder order : kOrders) {
    VerletList list(p.max_radius(), skin, order);
    list.build(p, static_cast<int>(p.size()), {});
    EXPECT_EQ(list.pairs().num_pairs(), brute.size());
    EXPECT_EQ(pairs_of(list, p), brute);
  }
}

// The deterministic order: every pair from its lower id, rows by increasing id, partners by
// increasing id, so each particle meets its partners in increasing id order.
TEST(VerletList, GlobalIdOrderVisitsEachParticlesPartnersInIdOrder) {
  ParticleStore p = random_particles(800, 0.015, 9);
  VerletList list(p.max_radius(), 0.4e-3, PairOrder::global_id);
  list.build(p, static_cast<int>(p.size()), {});
  std::map<GlobalId, GlobalId> last_partner;
  GlobalId last_row = -1;
  long visits = 0;
  for (std::size_t r = 0; r < list.pairs().num_rows(); ++r) {
    const GlobalId row = p.id[list.pairs().row_particle[r]];
    EXPECT_GT(row, last_row);
    last_row = row;
  }
  for_slots(list.pairs(), [&](int, int i, int j) {
    EXPECT_LT(p.id[i], p.id[j]);
    for (const auto& [self, other] : {std::pair{p.id[i], p.id[j]}, std::pair{p.id[j], p.id[i]}}) {
      auto it = last_partner.find(self);
      if (it != last_partner.end()) {
        EXPECT_GT(other, it->second);
      }
      last_partner[self] = other;
      ++visits;
    }
  });
  EXPECT_GT(visits, 1000);
}

TEST(VerletList, PositionsOutsideTheGridAreStillFound) {
  ParticleStore p;
  // Two touching grains far above the grid: both clamp into the top cells.
  p.add_sphere(1, 1e-3, 2650, Vec3(0.005, 0.005, 0.5), Vec3::Zero(), Vec3::Zero());
  p.add_sphere(2, 1e-3, 2650, Vec3(0.005, 0.005, 0.5019), Vec3::Zero(), Vec3::Zero());
  for (const PairOrder order : kOrders) {
    VerletList list(1e-3, 1e-4, order);
    list.build(p, 2, {});
    EXPECT_EQ(list.pairs().num_pairs(), 1u);
  }
}

TEST(VerletList, RebuildCarriesSpringsByGlobalId) {
  const double box = 0.01, skin = 0.3e-3;
  for (const PairOrder order : kOrders) {
    ParticleStore p = random_particles(400, box, 11);
    const double cell = 2.0 * p.max_radius() + skin;
    sort_by_cell(p, cell);
    VerletList list(p.max_radius(), skin, order);
    list.build(p, static_cast<int>(p.size()), {});
    ContactHistory history(HistoryKinds{true, false, false, false});
    history.restore(list.pairs(), list.walls(), p.id, {});
    // Give every pair a spring that encodes its ids, oriented as the force on the slot's i.
    std::map<std::pair<GlobalId, GlobalId>, Vec3> expected;  // force on the smaller id
    for_slots(list.pairs(), [&](int k, int i, int j) {
      const GlobalId a = p.id[i], b = p.id[j];
      const Vec3 s(static_cast<double>(a), static_cast<double>(b), 1.0);
      history.pair_spring[k] = TangentialSpring{s, 1.0};
      expected[{std::min(a, b), std::max(a, b)}] = a < b ? s : Vec3(-s);
    });
    std::vector<ContactHistoryRecord> records;
    history.collect(list.pairs(), list.walls(), p.id, false, records);
    sort_unique(records);
    // Move the particles a little (keeping all pairs inside the cut-off) and rebuild: the sort
    // by cell reorders them.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1e-5, 1e-5);
    for (auto& x : p.x) x += Vec3(u(rng), u(rng), u(rng));
    std::vector<int> reversed(p.size());  // a new local order of the same grains
    for (std::size_t i = 0; i < p.size(); ++i) reversed[i] = static_cast<int>(p.size() - 1 - i);
    p.permute(reversed);
    sort_by_cell(p, cell);
    list.build(p, static_cast<int>(p.size()), {});
    history.restore(list.pairs(), list.walls(), p.id, records);
    int checked = 0;
    for_slots(list.pairs(), [&](int k, int i, int j) {
      const GlobalId a = p.id[i], b = p.id[j];
      auto it = expected.find({std::min(a, b), std::max(a, b)});
      if (it == expected.end()) return;
      const Vec3 on_i = a < b ? it->second : Vec3(-it->second);
      EXPECT_EQ(history.pair_spring[k].force, on_i);
      ++checked;
    });
    EXPECT_GT(checked, 100);
  }
}

TEST(VerletList, NeedsRebuildAfterHalfSkin) {
  ParticleStore p = random_particles(10, 0.01, 5);
  VerletList list(p.max_radius(), 1e-4, PairOrder::local);
  list.build(p, static_cast<int>(p.size()), {});
  EXPECT_FALSE(list.needs_rebuild(p));
  p.x[3].x() += 0.49e-4;
  EXPECT_FALSE(list.needs_rebuild(p));
  p.x[3].x() += 0.02e-4;
  EXPECT_TRUE(list.needs_rebuild(p));
}
