#pragma once
// The spatial domain of one rank: its block of a Cartesian decomposition (decomposition.h;
// planes fixed or moved by the load balance, load_balance.h), the migration of particles
// between blocks, and the ghosts over the 26 neighbours (docs/parallel.md). Every exchange
// goes by the three stages x, then y, then z, each with the two face neighbours: forwarding
// what arrived in earlier stages reaches the 12 edge and 8 corner neighbours without
// messages to them (Plimpton 1995, J. Comput. Phys. 117:1, sec. 4). On one rank every
// neighbour is MPI_PROC_NULL and nothing is sent.
//
// The local store holds the owned particles first, then the ghosts, in the order they
// arrived: by stage, then face.
#include <mpi.h>

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "dem/core/box.h"
#include "dem/core/contact_history.h"
#include "dem/core/particle_store.h"
#include "dem/parallel/decomposition.h"
#include "dem/parallel/load_balance.h"
#include "dem/parallel/records.h"

namespace upgrain::dem {

struct DomainOptions {
  std::array<int, 3> blocks{0, 0, 0};  // {0,0,0}: chosen from the rank count and the box
  // Load balance (docs/parallel.md, "Load balance"): at the first neighbour-list rebuild at
  // or after every `balance_interval` steps, the planes move to the quantiles of
  // `balance_cost` along each cut axis; with `balance_at_start` also at the first rebuild.
  // 0: fixed (Eulerian) blocks.
  long balance_interval = 0;
  BalanceCost balance_cost = BalanceCost::particles;
  bool balance_at_start = true;
  // The axes along which the box is a periodic cell (docs/periodic.md); bounded by default.
  std::array<bool, 3> periodic{false, false, false};
  // How much larger than the box the periodic cell may grow (a deforming cell): its position
  // grid is sized for it (make_periodic_cell()).
  double cell_growth = 1.0;
  // An axis kept in one block: a sheared cell's shear axis, whose images across the gradient
  // axis's faces slide along it (docs/periodic.md, "Shear"). -1: none.
  int unsplit_axis = -1;
};

// The load balance so far (identical on every rank): the number of rebalances, the step of
// the last, and max/mean over ranks of the balanced cost just before it and once its rebuild
// is complete. 1 = perfect balance.
struct BalanceRecord {
  long count = 0;
  long last_step = -1;
  double before = 1.0;
  double after = 1.0;
};

// What a checkpoint keeps of a domain: the block planes and where the load balance stands
// (docs/restart.md). Reused on a restart with the same blocks; on another rank count the planes
// are balanced over the grains at once (Domain::restore).
struct DomainState {
  Box box;
  std::array<bool, 3> periodic{false, false, false};
  std::array<int, 3> blocks{1, 1, 1};
  std::array<std::vector<double>, 3> planes;  // blocks[d] + 1 per axis, the box faces included
  BalanceRecord balance;
  long next_balance_step = 0;
};

class Domain {
 public:
  // Collective over `comm`. `range`: the interaction range (largest diameter + skin), the
  // least block thickness and the depth of the ghost layer. `shapes`: shape and orientation
  // records travel with the particles.
  Domain(MPI_Comm comm, const Box& box, double range, bool shapes, const DomainOptions& options);

  [[nodiscard]] const Decomposition& decomposition() const { return *decomp_; }
  // The periodic cell moves (Decomposition::deform()); the ghosts take the new shifts at the
  // next refresh. Every rank alike.
  void deform_cell(const Box& cell_box) { decomp_->deform(cell_box); }
  // A sheared cell's images take `shear` (its offset on the grid of the shear axis).
  void shear_cell(const ShearImages& shear) { decomp_->set_shear(shear); }
  [[nodiscard]] MPI_Comm comm() const { return decomp_->comm(); }
  [[nodiscard]] int rank() const { return decomp_->rank(); }
  [[nodiscard]] int size() const { return decomp_->size(); }

  // Whether this rank holds ghosts: more than one rank, or a periodic axis (one rank is then
  // its own neighbour across the cell's faces, and its ghosts are images of its own grains).
  [[nodiscard]] bool has_ghosts() const { return size() > 1 || decomp_->cell().any(); }
  // Collective, at a rebuild (the store holds owned particles only). Along the periodic axes,
  // first puts every owned particle back into the cell, counting its crossings (wrap(),
  // dem/core/periodic_cell.h). Sends every particle
  // whose centroid left the block to the block that holds it now, with the history records
  // that involve it (a copy stays: the partner may stay). When a load balance is due, the
  // planes move first (`slots_per_owned`: the list slots of each owned particle, for the
  // pair-slot cost; another size counts 1 per particle). Throws upgrain::Error on every rank
  // when a particle moved farther than one block (naming it, `step` and `time`).
  void migrate(ParticleStore& p, std::vector<ContactHistoryRecord>& records,
               const std::vector<int>& slots_per_owned, long step, double time);
  // Collective, once the rebuild is complete: measures the balance a rebalance left.
  void measure_balance(int n_owned, const std::vector<int>& slots_per_owned);
  // Collective: appends to `p` (its owned particles) every particle of the other ranks within
  // the interaction range of this block, and remembers the routes. A particle sent across a
  // face of a periodic cell arrives as its image: shifted by the cell's length (exactly, on the
  // cell's grid) and its image counter by one, so its unwrapped position is its owner's.
  void build_ghosts(ParticleStore& p, int n_owned);
  // Collective: the ghosts' positions, velocities (and orientations) along the same routes.
  void refresh_ghosts(ParticleStore& p);
  // Collective, for the fast summation (newton on): what the force loop added to each ghost
  // in each of `fields` (vectors indexed by local particle) is sent back along the routes,
  // in reverse, and added to its owner's entry.
  void return_ghost_sums(std::span<std::vector<Vec3>* const> fields);
  // The rank that owns local ghost i (i >= n_owned), from the last build_ghosts().
  [[nodiscard]] int ghost_owner(std::size_t i) const { return ghost_owner_[i - n_owned_]; }

  [[nodiscard]] const BalanceRecord& balance() const { return balance_; }
  // The planes and the load balance's progress; and back (between steps): the planes when the
  // blocks are the same; on other blocks (another rank count), with the load balance on, planes
  // balanced over `positions` (every grain's once over the ranks, in any share: their counts are
  // summed; a rebalance at `step`), and otherwise the default planes. The balance's next step is
  // taken in every case. Collective.
  [[nodiscard]] DomainState state() const;
  void restore(const DomainState& s, const std::vector<Vec3>& positions, long step);
  [[nodiscard]] long migrated_out() const { return migrated_out_; }
  // Wall-clock seconds spent in messages and reductions by migrate() and build_ghosts().
  [[nodiscard]] double message_seconds() const { return message_seconds_; }

 private:
  bool rebalance_if_due(const ParticleStore& p, const std::vector<int>& slots_per_owned, long step);
  // Every cut axis's planes at the quantiles of `histogram` (3 axes x kBalanceBins).
  void place_planes(const long* histogram);
  void migration_pass(ParticleStore& p, std::vector<ContactHistoryRecord>& records);
  [[nodiscard]] long owned_cost(const std::vector<int>& slots_per_owned, int n_owned, int i) const;
  template <class Exchange>
  void timed(Exchange exchange);

  std::unique_ptr<Decomposition> decomp_;
  bool shapes_ = false;
  double range_ = 0.0;
  long migrated_out_ = 0;
  double message_seconds_ = 0.0;
  int n_owned_ = 0;  // at the last build_ghosts()

  struct {
    long interval = 0;
    BalanceCost cost = BalanceCost::particles;
    long next_step = 0;
    bool measure_after = false;
    std::vector<long> histogram, reduced;  // 3 axes x kBalanceBins, then the total cost
  } balance_state_;
  BalanceRecord balance_;

  // Ghost routes of the last build, per axis and face: the local indices sent and where the
  // received ghosts start in the store.
  std::array<std::array<std::vector<int>, 2>, 3> ghost_send_;
  std::array<std::array<int, 2>, 3> ghost_recv_start_{};
  std::array<std::array<int, 2>, 3> ghost_recv_count_{};
  // Shifts each route's ghosts by its image shift along its axis (ghost routes of a periodic
  // cell's faces), from record index `first` on.
  template <class Record>
  void shift_images(std::vector<Record>& out, int d, int s) const;
  // A sheared cell: the ghosts that cross the gradient axis's faces through side s also slide by
  // the offset along the shear axis, and at a build are wrapped into the cell along it by whole
  // lengths, m of them, which `ghost_slide_[s]` keeps for the refreshes (docs/periodic.md,
  // "Shear").
  template <class Record>
  void slide_images(std::vector<Record>& out, int s, bool build);
  std::array<std::vector<int>, 2> ghost_slide_;
  // The ghost stages' axes in order: the gradient axis of a sheared cell first (its images, slid
  // and wrapped along the shear axis, then take their images along the others), else x, y, z.
  [[nodiscard]] std::array<int, 3> stage_axes() const;
  std::vector<int> ghost_owner_;
  // Message buffers, kept between steps (a ghost refresh allocates nothing after warm-up).
  std::array<std::vector<StateRecord>, 2> ghost_out_, ghost_in_;  // a ghost arrives whole at a build
  std::array<std::vector<MotionRecord>, 2> motion_out_, motion_in_;
  std::array<std::vector<StateRecord>, 2> state_out_, state_in_;
  std::array<std::vector<ContactHistoryRecord>, 2> history_out_, history_in_;
  std::array<std::vector<ShapeRecord>, 2> shape_out_, shape_in_;
  std::array<std::vector<OrientationRecord>, 2> orientation_out_, orientation_in_;
  std::array<std::vector<double>, 2> sums_out_, sums_in_;
};

}  // namespace upgrain::dem
