#pragma once
// The history of every contact a rank evaluates, in one store kept apart from the neighbour
// lists (docs/architecture.md, "Contact history"). A contact's history is what its law
// carries from one step to the next:
//  - the incremental Mindlin spring (dem/contact/contact_response.h);
//  - the rolling spring (dem/contact/rolling_resistance.h);
//  - for pairs with an ellipsoid, the contact memory: the last normal (the contact solver's
//    warm start), the Hertz radius held from first touch and the proven separation budget
//    (dem/contact/geometry/support_function_pair.h).
// Between neighbour-list rebuilds the store holds one history per pair slot and per wall
// entry of the current lists (dem/core/pair_list.h), addressed by index, so the force loop
// does no look-up per contact. At a rebuild the histories of active contacts leave the store
// as ContactHistoryRecords keyed by global ids, travel with migrating particles, and come
// back into the slots of the new lists. The record is flat and versioned: the unit of
// migration and of a checkpoint.
#include <type_traits>
#include <vector>

#include "dem/core/pair_list.h"
#include "dem/core/types.h"

namespace upgrain::dem {

// History of one contact's incremental Mindlin spring.
struct TangentialSpring {
  Vec3 force = Vec3::Zero();  // tangential force on body i
  double stiffness = 0.0;     // k_t when the force was last updated (0: new contact)

  [[nodiscard]] TangentialSpring reversed() const { return {-force, stiffness}; }
};

// History of one contact's rolling spring, and of its twisting spring when the scene has
// twisting resistance.
struct RollingSpring {
  Vec3 torque = Vec3::Zero();    // spring torque on body i (body j receives -torque)
  double stiffness = 0.0;        // k_r when the torque was last updated (0: new contact)
  double twist = 0.0;            // twisting torque on body i about the normal from i to j
  double twist_stiffness = 0.0;  // k_tw when it was last updated

  // Seen from j, both the normal and the torque change sign: the twist about the normal is the
  // same number.
  [[nodiscard]] RollingSpring reversed() const { return {-torque, stiffness, twist, twist_stiffness}; }
};

// What an ellipsoid contact keeps between steps besides its springs: the last normal (the
// contact solver's warm start; zero when none) and the Hertz radius frozen at first touch
// (0 while apart). A radius that followed the contact point would make the normal force
// non-conservative: static equilibria then stop being attracting (docs/ellipsoids.md).
struct ShapedContactMemory {
  Vec3 normal = Vec3::Zero();
  double r_star = 0.0;
  // A pair proven apart: the gap still proven after the grains' motion since (m; 0 when none).
  // It rests on the grains' motion bounds (dem/contact/grain_poses.h), which follow a grain
  // only while it keeps its local index; with deterministic summation it is dropped at every
  // rebuild, since local indices then depend on the decomposition.
  double gap_budget = 0.0;

  [[nodiscard]] bool empty() const { return r_star == 0.0 && normal == Vec3::Zero(); }
  [[nodiscard]] ShapedContactMemory reversed() const { return {-normal, r_star, gap_budget}; }
};

// One contact's whole history keyed by global ids: a pair (a < b), oriented from a (the
// spring force and torque on a, the normal from a to b); or a wall contact of particle a with
// wall w, stored as b = -1 - w. Trivially copyable: it travels as bytes.
struct ContactHistoryRecord {
  static constexpr int kVersion = 2;  // of this layout, for files that store records (2: twisting)

  GlobalId a = 0, b = 0;
  double tangential_force[3] = {0, 0, 0};
  double tangential_stiffness = 0.0;
  double rolling_torque[3] = {0, 0, 0};
  double rolling_stiffness = 0.0;
  double twisting_torque = 0.0;
  double twisting_stiffness = 0.0;
  double normal[3] = {0, 0, 0};
  double r_star = 0.0;
  double gap_budget = 0.0;

  bool operator<(const ContactHistoryRecord& o) const { return a < o.a || (a == o.a && b < o.b); }
  [[nodiscard]] bool same_key(const ContactHistoryRecord& o) const { return a == o.a && b == o.b; }
};
static_assert(std::is_trivially_copyable_v<ContactHistoryRecord>);

// The key of wall w as the second id of a record.
inline GlobalId wall_key(int w) { return -1 - static_cast<GlobalId>(w); }

// Which histories a scene's law carries (the rest of the store stays empty).
struct HistoryKinds {
  bool tangential = false;       // between particles
  bool wall_tangential = false;  // at walls
  bool rolling = false;          // rolling resistance, pairs and walls
  bool shapes = false;           // contact memory of pairs, held Hertz radius at walls
};

class ContactHistory {
 public:
  explicit ContactHistory(HistoryKinds kinds = {}) : kinds_(kinds) {}
  [[nodiscard]] const HistoryKinds& kinds() const { return kinds_; }
  // Bytes the store holds (its arrays' sizes): what the force loop reads and writes of it
  // per evaluation.
  [[nodiscard]] std::size_t bytes() const {
    return pair_spring.size() * sizeof(TangentialSpring) + pair_rolling.size() * sizeof(RollingSpring) +
           pair_memory.size() * sizeof(ShapedContactMemory) + wall_spring.size() * sizeof(TangentialSpring) +
           wall_rolling.size() * sizeof(RollingSpring) + wall_r_star.size() * sizeof(double);
  }

  // Per pair slot of the current PairList, oriented from the slot's first particle.
  std::vector<TangentialSpring> pair_spring;
  std::vector<RollingSpring> pair_rolling;
  std::vector<ShapedContactMemory> pair_memory;
  // Per entry of the current WallList.
  std::vector<TangentialSpring> wall_spring;
  std::vector<RollingSpring> wall_rolling;
  std::vector<double> wall_r_star;  // Hertz radius held from first touch (ellipsoids)

  // Appends a record for every slot and entry with some history (`id`: global ids by local
  // index). Without `keep_gap_budget` the separation budgets are left out.
  void collect(const PairList& pairs, const WallList& walls, const std::vector<GlobalId>& id,
               bool keep_gap_budget, std::vector<ContactHistoryRecord>& out) const;
  // Sizes the store for new lists and gives each slot and entry its record from `records`
  // (sorted, no repeated key), oriented as the slot; the others start empty.
  void restore(const PairList& pairs, const WallList& walls, const std::vector<GlobalId>& id,
               const std::vector<ContactHistoryRecord>& records);

 private:
  HistoryKinds kinds_;
};

// Sorts records and removes repeated keys (a pair across two ranks arrives from both, with
// equal histories).
void sort_unique(std::vector<ContactHistoryRecord>& records);

}  // namespace upgrain::dem
