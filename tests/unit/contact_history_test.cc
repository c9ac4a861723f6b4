// The contact-history store: every active history leaves as one record keyed by the pair of
// global ids (oriented from the lower id), inactive slots leave nothing, and a record comes back
// into any slot of the same pair in that slot's orientation; wall contacts are keyed by wall.
#include "dem/core/contact_history.h"

#include <gtest/gtest.h>

using namespace upgrain::dem;

namespace {
// One row: local particle 0 (id 20) with partners 1 (id 10) and 2 (id 30).
PairList one_row() {
  PairList l;
  l.row_particle = {0};
  l.row_start = {0, 2};
  l.partner = {1, 2};
  return l;
}
const std::vector<GlobalId> kIds = {20, 10, 30};
}  // namespace

TEST(ContactHistory, RecordsAreKeyedAndOrientedFromTheLowerId) {
  ContactHistory h(HistoryKinds{true, true, true, true});
  const PairList pairs = one_row();
  WallList walls;
  walls.particle = {2};
  walls.wall = {3};
  h.restore(pairs, walls, kIds, {});
  ASSERT_EQ(h.pair_spring.size(), 2u);
  // Slot 0: body i has id 20, body j id 10 (the lower): the record is turned.
  h.pair_spring[0] = {Vec3(1, 2, 3), 4.0};
  h.pair_rolling[0] = {Vec3(5, 6, 7), 8.0, 0.25, 11.0};  // the twist: a torque about the normal
  h.pair_memory[0] = {Vec3(0, 0, 1), 2e-3, 1e-6};
  // Slot 1: nothing to carry.
  h.wall_spring[0] = {Vec3(9, 9, 9), 1.5};
  h.wall_r_star[0] = 3e-3;
  std::vector<ContactHistoryRecord> kept, dropped;
  h.collect(pairs, walls, kIds, true, kept);
  h.collect(pairs, walls, kIds, false, dropped);
  ASSERT_EQ(kept.size(), 2u);  // one pair, one wall contact
  const ContactHistoryRecord& r = kept[0];
  EXPECT_EQ(r.a, 10);
  EXPECT_EQ(r.b, 20);
  EXPECT_EQ(Vec3(r.tangential_force[0], r.tangential_force[1], r.tangential_force[2]), Vec3(-1, -2, -3));
  EXPECT_EQ(r.tangential_stiffness, 4.0);
  EXPECT_EQ(Vec3(r.rolling_torque[0], r.rolling_torque[1], r.rolling_torque[2]), Vec3(-5, -6, -7));
  // Torque and normal both turn: the twist about the normal is the same number seen from j.
  EXPECT_EQ(r.twisting_torque, 0.25);
  EXPECT_EQ(r.twisting_stiffness, 11.0);
  EXPECT_EQ(Vec3(r.normal[0], r.normal[1], r.normal[2]), Vec3(0, 0, -1));
  EXPECT_EQ(r.r_star, 2e-3);
  EXPECT_EQ(r.gap_budget, 1e-6);
  EXPECT_EQ(dropped[0].gap_budget, 0.0);
  EXPECT_EQ(kept[1].a, 30);
  EXPECT_EQ(kept[1].b, wall_key(3));
  EXPECT_EQ(kept[1].tangential_stiffness, 1.5);
  EXPECT_EQ(kept[1].r_star, 3e-3);

  // Back into a list where the pair is seen from id 10 (local 0), and the grain with id 30 at
  // another local index near the same wall.
  sort_unique(kept);
  PairList turned;
  turned.row_particle = {0};
  turned.row_start = {0, 1};
  turned.partner = {1};
  const std::vector<GlobalId> ids = {10, 20, 30};
  WallList near;
  near.particle = {2};
  near.wall = {3};
  ContactHistory back(HistoryKinds{true, true, true, true});
  back.restore(turned, near, ids, kept);
  EXPECT_EQ(back.pair_spring[0].force, Vec3(-1, -2, -3));
  EXPECT_EQ(back.pair_rolling[0].torque, Vec3(-5, -6, -7));
  EXPECT_EQ(back.pair_rolling[0].twist, 0.25);
  EXPECT_EQ(back.pair_rolling[0].twist_stiffness, 11.0);
  EXPECT_EQ(back.pair_memory[0].normal, Vec3(0, 0, -1));
  EXPECT_EQ(back.wall_spring[0].force, Vec3(9, 9, 9));
  EXPECT_EQ(back.wall_r_star[0], 3e-3);
  // The original orientation gives the original values.
  ContactHistory again(HistoryKinds{true, true, true, true});
  again.restore(pairs, walls, kIds, kept);
  EXPECT_EQ(again.pair_spring[0].force, Vec3(1, 2, 3));
  EXPECT_EQ(again.pair_memory[0].normal, Vec3(0, 0, 1));
  EXPECT_EQ(again.pair_spring[1].stiffness, 0.0);  // no record: a new contact
}

TEST(ContactHistory, OnlyTheKindsOfTheSceneAreKept) {
  ContactHistory h(HistoryKinds{true, false, false, false});
  const PairList pairs = one_row();
  h.restore(pairs, WallList{}, kIds, {});
  EXPECT_EQ(h.pair_spring.size(), 2u);
  EXPECT_TRUE(h.pair_rolling.empty());
  EXPECT_TRUE(h.pair_memory.empty());
  EXPECT_TRUE(h.wall_spring.empty());
}

TEST(ContactHistory, RepeatedKeysFromTwoRanksCollapseToOne) {
  ContactHistoryRecord a, b, c;
  a.a = b.a = 1;
  a.b = b.b = 2;
  c.a = 0;
  c.b = 5;
  std::vector<ContactHistoryRecord> r = {a, c, b};
  sort_unique(r);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].a, 0);
  EXPECT_EQ(r[1].b, 2);
}
