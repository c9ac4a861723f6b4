// Output written by every rank without a gather (docs/output.md, "Force network"; docs/parallel.md,
// "Output"): each rank's contacts of its rows, in rank order, are the contacts gathered on rank 0;
// the grains of other rows that its pairs reach are those of the whole state, bit for bit; and
// the network each rank resolves from them is the one resolved from the whole state.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstring>
#include <vector>

#include "../common/scenes.h"
#include "dem/engine/simulation.h"
#include "dem/io/force_network.h"
#include "dem/parallel/exchange.h"
#include "helpers.h"

using namespace upgrain;
using namespace upgrain::dem;

namespace {

// A grain as compared: its id and centre.
struct GrainAt {
  GlobalId id;
  double x[3];
};

// The numbers of a resolved contact that the network file holds.
struct Resolved {
  GlobalId a, b;
  std::int64_t wall;
  double numbers[16];
};

Resolved resolved(const io::NetworkContact& c) {
  Resolved r{c.a, c.b, c.wall, {}};
  const Vec3* v[] = {&c.point, &c.normal, &c.branch, &c.normal_force, &c.tangential_force};
  for (int k = 0; k < 5; ++k)
    for (int d = 0; d < 3; ++d) r.numbers[3 * k + d] = (*v[k])[d];
  r.numbers[15] = c.overlap;
  return r;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace

TEST(OutputRows, EachRanksContactsAndPartnersResolveTheGatheredNetwork) {
  const SceneConfig scene = test::deposition_scene(600);
  Simulation world(scene, fill_container(scene), MPI_COMM_WORLD);
  world.run(2999);  // mid-deposition: impacts, the first compaction
  world.request_contacts();
  world.step();
  const ParticleStore state = world.gather_sorted_by_id();
  const std::vector<ContactRecord> gathered = world.gather_contacts_by_id();

  IdSlice slice = world.whole_state_slice();
  const std::size_t rows = slice.rows;
  const std::vector<ContactRecord> mine = world.contacts_of_rows(slice);
  const io::NetworkGrains grains{slice.grains, slice.first_row, slice.rows};
  std::vector<GrainAt> partners;
  for (std::size_t k = rows; k < slice.grains.size(); ++k) {
    partners.push_back({slice.grains.id[k], {}});
    put(partners.back().x, slice.grains.x[k]);
  }
  long outside = 0;  // contacts whose first grain is not a row of this rank
  for (const ContactRecord& c : mine)
    outside += c.a < slice.first_row || c.a >= slice.first_row + static_cast<long>(rows);
  EXPECT_EQ(outside, 0);
  const std::vector<io::NetworkContact> network =
      io::force_network(grains, world.walls(), mine, world.decomposition().cell());
  std::vector<Resolved> share;
  for (const io::NetworkContact& c : network) share.push_back(resolved(c));

  const std::vector<ContactRecord> all = gather_to_root(mine, MPI_COMM_WORLD);
  const std::vector<GrainAt> reached = gather_to_root(partners, MPI_COMM_WORLD);
  const std::vector<Resolved> resolved_by_rows = gather_to_root(share, MPI_COMM_WORLD);
  if (world.rank() != 0) return;
  ASSERT_GT(gathered.size(), 500u);  // 876 pair and wall contacts
  EXPECT_TRUE(same_bytes(all, gathered))
      << all.size() << " contacts from the rows, " << gathered.size() << " gathered";
  long differing = 0;
  for (const GrainAt& g : reached) {
    const auto i = static_cast<std::size_t>(g.id);
    differing += state.id[i] != g.id || get(g.x) != state.x[i];
  }
  EXPECT_EQ(differing, 0) << "of " << reached.size() << " partners from other rows";
  if (world.ranks() > 1) {
    EXPECT_GT(reached.size(), 0u);
  }
  std::vector<Resolved> whole;
  for (const io::NetworkContact& c :
       io::force_network(state, world.walls(), gathered, world.decomposition().cell()))
    whole.push_back(resolved(c));
  EXPECT_TRUE(same_bytes(resolved_by_rows, whole));
}
