#include "dem/parallel/domain.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "dem/parallel/exchange.h"

namespace upgrain::dem {

namespace {

constexpr int kTagMigrate = 100;
constexpr int kTagHistory = 200;
constexpr int kTagGhosts = 300;
constexpr int kTagRefresh = 400;
constexpr int kTagShapes = 500;        // migration, next to kTagMigrate
constexpr int kTagGhostShapes = 700;   // next to kTagGhosts
constexpr int kTagOrientations = 800;  // next to kTagRefresh
constexpr int kTagSums = 900;          // ghost sums returned to their owners

// The records that involve a particle of `leaving` (sorted), appended to out.
void records_of(const std::vector<ContactHistoryRecord>& records, const std::vector<GlobalId>& leaving,
                std::vector<ContactHistoryRecord>& out) {
  for (const ContactHistoryRecord& r : records) {
    if (std::binary_search(leaving.begin(), leaving.end(), r.a) ||
        (r.b >= 0 && std::binary_search(leaving.begin(), leaving.end(), r.b)))
      out.push_back(r);
  }
}

std::string block_name(const std::array<int, 3>& c) {
  std::ostringstream m;
  m << "(" << c[0] << ", " << c[1] << ", " << c[2] << ")";
  return m.str();
}

}  // namespace

Domain::Domain(MPI_Comm comm, const Box& box, double range, bool shapes, const DomainOptions& options)
    : decomp_(std::make_unique<Decomposition>(comm, box, range, options.blocks, options.periodic,
                                              options.cell_growth, options.unsplit_axis)),
      shapes_(shapes),
      range_(range) {
  if (options.balance_interval < 0) throw Error("load balance: balance_interval must be >= 0 steps");
  balance_state_.interval = options.balance_interval;
  balance_state_.cost = options.balance_cost;
  balance_state_.next_step = options.balance_at_start ? 0 : options.balance_interval;
}

DomainState Domain::state() const {
  const Decomposition& dec = *decomp_;
  DomainState s;
  s.box = dec.box();
  s.periodic = dec.cell().periodic;
  s.blocks = dec.blocks();
  for (int d = 0; d < 3; ++d)
    for (int k = 0; k <= s.blocks[d]; ++k) s.planes[d].push_back(dec.plane(d, k));
  s.balance = balance_;
  s.next_balance_step = balance_state_.next_step;
  return s;
}

void Domain::restore(const DomainState& s, const std::vector<Vec3>& positions, long step) {
  balance_state_.next_step = s.next_balance_step;
  Decomposition& dec = *decomp_;
  if (s.blocks == dec.blocks()) {
    for (int d = 0; d < 3; ++d) {
      if (s.planes[d].size() != static_cast<std::size_t>(s.blocks[d] + 1)) continue;
      dec.set_cuts(d, std::vector<double>(s.planes[d].begin() + 1, s.planes[d].end() - 1));
    }
    balance_ = s.balance;
    return;
  }
  // Other blocks (another rank count): the checkpoint's planes do not apply, and the default
  // ones can leave the grains on a few ranks for good, since a bed at rest is never rebuilt and
  // so never rebalanced. With the load balance on, the planes go where a fresh run's first
  // rebuild puts them: to the quantiles of the grains (one each; the pair slots are not known
  // before the lists), from `positions`, whose counts per bin and per rank are summed over the
  // ranks (integers: the same on every rank, whichever rank holds which grains), so that every
  // rank places the same planes.
  if (balance_state_.interval <= 0 || dec.size() < 2) return;
  balance_ = s.balance;
  const std::array<int, 3>& blocks = dec.blocks();
  const Box& box = dec.box();
  std::vector<long>& h = balance_state_.reduced;
  h.assign(3 * static_cast<std::size_t>(kBalanceBins) + 1, 0);
  for (const Vec3& x : positions)
    for (int d = 0; d < 3; ++d)
      if (blocks[d] > 1) ++h[d * kBalanceBins + balance_bin(x[d], box.lo[d], box.hi[d], kBalanceBins)];
  MPI_Allreduce(MPI_IN_PLACE, h.data(), static_cast<int>(h.size()), MPI_LONG, MPI_SUM, comm());
  auto imbalance = [&] {
    std::vector<long> owned(static_cast<std::size_t>(dec.size()) + 1, 0);  // per rank, then the total
    for (const Vec3& x : positions) ++owned[static_cast<std::size_t>(dec.owner_of(x))];
    owned.back() = static_cast<long>(positions.size());
    MPI_Allreduce(MPI_IN_PLACE, owned.data(), static_cast<int>(owned.size()), MPI_LONG, MPI_SUM, comm());
    return imbalance_ratio(*std::max_element(owned.begin(), owned.end() - 1), owned.back(), dec.size());
  };
  balance_.before = imbalance();
  place_planes(h.data());
  balance_.after = imbalance();
  ++balance_.count;
  balance_.last_step = step;
}

void Domain::place_planes(const long* histogram) {
  Decomposition& dec = *decomp_;
  const std::array<int, 3>& blocks = dec.blocks();
  const Box& box = dec.box();
  for (int d = 0; d < 3; ++d) {
    if (blocks[d] < 2) continue;
    std::vector<double> cuts =
        quantile_cuts(histogram + d * kBalanceBins, kBalanceBins, box.lo[d], box.hi[d], blocks[d]);
    // Along a periodic axis the border blocks have neighbours across the cell's faces: they too
    // stay one range thick (planes at least a range inside the cell).
    const double inset = dec.periodic(d) ? dec.min_block() : 0.0;
    clamp_cuts(cuts, box.lo[d] + inset, box.hi[d] - inset, dec.min_block());
    dec.set_cuts(d, cuts);
  }
}

template <class Exchange>
void Domain::timed(Exchange exchange) {
  const std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  exchange();
  message_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void Domain::migrate(ParticleStore& p, std::vector<ContactHistoryRecord>& records,
                     const std::vector<int>& slots_per_owned, long step, double time) {
  const Decomposition& dec = *decomp_;
  const std::array<int, 3>& me = dec.coords();
  const int n = static_cast<int>(p.size());
  // Back into the periodic cell, counting the crossings (every rank, one rank included).
  const PeriodicCell& cell = dec.cell();
  if (cell.any())
    for (int i = 0; i < n; ++i) wrap(cell, p.x[i], p.image[i]);
  // How many blocks apart along axis d: the shorter way round a periodic axis.
  auto apart = [&](const std::array<int, 3>& c, int d) {
    const int k = std::abs(c[d] - me[d]);
    return dec.periodic(d) ? std::min(k, dec.blocks()[d] - k) : k;
  };
  // A particle may only move to an adjacent block between two rebuilds: farther, and the
  // ghosts it should have met were never here. Stop, naming it, rather than lose contacts.
  std::string message;
  for (int i = 0; i < n && message.empty(); ++i) {
    const std::array<int, 3> c = dec.block_of(p.x[i]);
    if (apart(c, 0) > 1 || apart(c, 1) > 1 || apart(c, 2) > 1) {
      std::ostringstream m;
      m << "particle " << p.id[i] << " at (" << p.x[i][0] << ", " << p.x[i][1] << ", " << p.x[i][2]
        << ") m moved from block " << block_name(me) << " (rank " << dec.rank() << ") to block "
        << block_name(c) << ", farther than one block, by step " << step << " (t = " << time
        << " s); the time step is too large or the particle was ejected";
      message = m.str();
    }
  }
  timed([&] { throw_if_any(comm(), message); });

  // The check above used the planes the particles were last sorted by; a rebalance moves
  // them only now. A particle may then be several blocks from home: each pass moves it one
  // block along every axis, and a global reduction decides whether another pass is needed
  // (at most max(blocks) - 1 passes; the records travel with it at every hop).
  if (!rebalance_if_due(p, slots_per_owned, step)) {
    migration_pass(p, records);
    return;
  }
  const std::array<int, 3>& b = dec.blocks();
  const int max_passes = std::max({b[0], b[1], b[2]});
  for (int pass = 1;; ++pass) {
    migration_pass(p, records);
    int away = 0;
    for (std::size_t i = 0; i < p.size() && away == 0; ++i) away = dec.block_of(p.x[i]) == me ? 0 : 1;
    int any_away = 0;
    timed([&] { MPI_Allreduce(&away, &any_away, 1, MPI_INT, MPI_MAX, comm()); });
    if (any_away == 0) return;
    // Collective: every rank sees the same any_away and pass.
    if (pass >= max_passes)
      throw Error("load balance: particles still away from their blocks after migration");
  }
}

void Domain::migration_pass(ParticleStore& p, std::vector<ContactHistoryRecord>& records) {
  const Decomposition& dec = *decomp_;
  const std::array<int, 3>& me = dec.coords();
  std::array<std::vector<GlobalId>, 2> leaving;
  for (int d = 0; d < 3; ++d) {
    for (int s = 0; s < 2; ++s) {
      state_out_[s].clear();
      history_out_[s].clear();
      shape_out_[s].clear();
      leaving[s].clear();
    }
    // Compact the owned particles in place, packing the leavers.
    const std::size_t n = p.size();
    std::size_t keep = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const int c = dec.block_of(p.x[i])[d];
      if (c != me[d]) {
        const int s = dec.step_towards(d, c) < 0 ? 0 : 1;
        const StateRecord r = pack_state(p, i);
        state_out_[s].push_back(r);
        if (shapes_) shape_out_[s].push_back(pack_shape(p, i));
        leaving[s].push_back(r.gid);
        continue;
      }
      if (keep != i) copy_particle(p, i, keep);
      ++keep;
    }
    truncate_store(p, keep);
    // Every record of a leaver goes with it (a copy stays: the partner may stay here).
    for (int s = 0; s < 2; ++s) {
      std::sort(leaving[s].begin(), leaving[s].end());
      if (!leaving[s].empty()) records_of(records, leaving[s], history_out_[s]);
    }
    const std::array<int, 2> nb{dec.neighbor(d, 0), dec.neighbor(d, 1)};
    timed([&] {
      exchange_along_axis(comm(), nb, state_out_, state_in_, false, kTagMigrate + 10 * d);
      exchange_along_axis(comm(), nb, history_out_, history_in_, false, kTagHistory + 10 * d);
      if (shapes_) exchange_along_axis(comm(), nb, shape_out_, shape_in_, false, kTagShapes + 10 * d);
    });
    for (int s = 0; s < 2; ++s) {
      migrated_out_ += static_cast<long>(state_out_[s].size());
      for (const StateRecord& r : state_in_[s]) append_state(p, r);
      records.insert(records.end(), history_in_[s].begin(), history_in_[s].end());
      if (shapes_)
        for (const ShapeRecord& r : shape_in_[s]) append_shape(p, r);
    }
  }
}

std::array<int, 3> Domain::stage_axes() const {
  const ShearImages& le = decomp_->cell().shear;
  if (!le.any()) return {0, 1, 2};
  std::array<int, 3> order{le.gradient, 0, 0};
  for (int d = 0, k = 1; d < 3; ++d)
    if (d != le.gradient) order[static_cast<std::size_t>(k++)] = d;
  return order;
}

void Domain::build_ghosts(ParticleStore& p, int n_owned) {
  const Decomposition& dec = *decomp_;
  const Box& block = dec.block();
  n_owned_ = n_owned;
  for (int d : stage_axes()) {
    for (int s = 0; s < 2; ++s) {
      std::vector<int>& send = ghost_send_[d][s];
      send.clear();
      ghost_out_[s].clear();
      shape_out_[s].clear();
      if (dec.neighbor(d, s) == MPI_PROC_NULL) continue;
      // Everything within the interaction range of the face, ghosts of earlier stages
      // included (they cover the edges and corners).
      const double bound = s == 0 ? block.lo[d] + range_ : block.hi[d] - range_;
      const int n = static_cast<int>(p.size());
      for (int i = 0; i < n; ++i) {
        if (s == 0 ? p.x[i][d] < bound : p.x[i][d] > bound) send.push_back(i);
      }
      for (int i : send) {
        ghost_out_[s].push_back(pack_state(p, static_cast<std::size_t>(i)));
        if (shapes_) shape_out_[s].push_back(pack_shape(p, static_cast<std::size_t>(i)));
      }
      shift_images(ghost_out_[s], d, s);
      if (d == dec.cell().shear.gradient) slide_images(ghost_out_[s], s, true);
    }
    const std::array<int, 2> nb{dec.neighbor(d, 0), dec.neighbor(d, 1)};
    timed([&] {
      exchange_along_axis(comm(), nb, ghost_out_, ghost_in_, false, kTagGhosts + 10 * d);
      if (shapes_) exchange_along_axis(comm(), nb, shape_out_, shape_in_, false, kTagGhostShapes + 10 * d);
    });
    for (int s = 0; s < 2; ++s) {
      ghost_recv_start_[d][s] = static_cast<int>(p.size());
      ghost_recv_count_[d][s] = static_cast<int>(ghost_in_[s].size());
      for (const StateRecord& r : ghost_in_[s]) append_state(p, r);
      if (shapes_)
        for (const ShapeRecord& r : shape_in_[s]) append_shape(p, r);
    }
  }
  // Every particle is inside its owner's block at a build (migration has just run), so the
  // block holding a ghost's centroid names its owner.
  // An image lies outside the cell: its owner holds it wrapped.
  ghost_owner_.resize(p.size() - static_cast<std::size_t>(n_owned));
  for (std::size_t k = 0; k < ghost_owner_.size(); ++k) {
    Vec3 x = p.x[static_cast<std::size_t>(n_owned) + k];
    ImageCount image{0, 0, 0};
    wrap(dec.cell(), x, image);
    ghost_owner_[k] = dec.owner_of(x);
  }
}

// A record's position along d moved by the route's image shift, and its image counter the
// other way (the unwrapped position stays its owner's). The shift is a whole number of the
// cell's quanta and the position is on the grid: the sum is exact (periodic_cell.h).
template <class Record>
void Domain::shift_images(std::vector<Record>& out, int d, int s) const {
  const double shift = decomp_->image_shift(d, s);
  if (shift == 0.0) return;
  const int count = shift > 0.0 ? -1 : 1;
  for (Record& r : out) {
    r.x[d] += shift;
    if constexpr (requires { r.image; }) r.image[d] += count;
  }
}

template <class Record>
void Domain::slide_images(std::vector<Record>& out, int s, bool build) {
  const PeriodicCell& cell = decomp_->cell();
  const ShearImages& le = cell.shear;
  const double shift = decomp_->image_shift(le.gradient, s);
  if (shift == 0.0) return;
  // Through the lower face (shift +L_g) the images are those across the upper face: x + L_g e_g
  // + offset e_s; and the other way. Sums on the grid: exact.
  const double slide = shift > 0.0 ? le.offset : -le.offset;
  const auto turns = static_cast<std::int32_t>(shift > 0.0 ? le.turns : -le.turns);
  const int a = le.shear;
  const double lo = cell.box.lo[a], hi = cell.box.hi[a], l = hi - lo;
  std::vector<int>& wraps = ghost_slide_[static_cast<std::size_t>(s)];
  if (build) wraps.assign(out.size(), 0);
  for (std::size_t k = 0; k < out.size(); ++k) {
    Record& r = out[k];
    r.x[a] += slide;
    if (build) {
      // Into the cell along the shear axis, the one block there: the later stages take its images.
      int m = 0;
      while (r.x[a] + m * l >= hi) --m;
      while (r.x[a] + m * l < lo) ++m;
      wraps[k] = m;
    }
    const int m = wraps[k];
    if (m != 0) r.x[a] += m * l;
    // The unwrapped position stays the owner's (periodic_cell.h, unwrapped()).
    if constexpr (requires { r.image; }) r.image[a] += turns - m;
  }
}

void Domain::refresh_ghosts(ParticleStore& p) {
  const Decomposition& dec = *decomp_;
  for (int d : stage_axes()) {
    for (int s = 0; s < 2; ++s) {
      const std::vector<int>& send = ghost_send_[d][s];
      motion_out_[s].resize(send.size());
      for (std::size_t k = 0; k < send.size(); ++k) {
        MotionRecord& r = motion_out_[s][k];
        put(r.x, p.x[send[k]]);
        put(r.v, p.v[send[k]]);
        put(r.omega, p.omega[send[k]]);
      }
      shift_images(motion_out_[s], d, s);
      if (d == dec.cell().shear.gradient) slide_images(motion_out_[s], s, false);
      motion_in_[s].resize(static_cast<std::size_t>(ghost_recv_count_[d][s]));
      if (shapes_) {
        orientation_out_[s].resize(send.size());
        for (std::size_t k = 0; k < send.size(); ++k) put(orientation_out_[s][k].q, p.orientation[send[k]]);
        orientation_in_[s].resize(static_cast<std::size_t>(ghost_recv_count_[d][s]));
      }
    }
    const std::array<int, 2> nb{dec.neighbor(d, 0), dec.neighbor(d, 1)};
    exchange_along_axis(comm(), nb, motion_out_, motion_in_, true, kTagRefresh + 10 * d);
    if (shapes_)
      exchange_along_axis(comm(), nb, orientation_out_, orientation_in_, true, kTagOrientations + 10 * d);
    for (int s = 0; s < 2; ++s) {
      const int start = ghost_recv_start_[d][s];
      for (std::size_t k = 0; k < motion_in_[s].size(); ++k) {
        const MotionRecord& r = motion_in_[s][k];
        const std::size_t i = static_cast<std::size_t>(start) + k;
        p.x[i] = get(r.x);
        p.v[i] = get(r.v);
        p.omega[i] = get(r.omega);
      }
      if (shapes_)
        for (std::size_t k = 0; k < orientation_in_[s].size(); ++k)
          p.orientation[static_cast<std::size_t>(start) + k] = get_quaternion(orientation_in_[s][k].q);
    }
  }
}

void Domain::return_ghost_sums(std::span<std::vector<Vec3>* const> fields) {
  const Decomposition& dec = *decomp_;
  const std::size_t f = fields.size();
  // The stages in reverse: what a ghost of stage z collected goes back to the rank that sent
  // it, where it may itself be a ghost of stage y or x and travels on in the next stage.
  const std::array<int, 3> stages = stage_axes();
  for (auto it = stages.rbegin(); it != stages.rend(); ++it) {
    const int d = *it;
    for (int s = 0; s < 2; ++s) {
      const int start = ghost_recv_start_[d][s];
      const int count = ghost_recv_count_[d][s];
      std::vector<double>& out = sums_out_[s];
      out.resize(static_cast<std::size_t>(count) * 3 * f);
      double* o = out.data();
      for (int k = 0; k < count; ++k)
        for (const std::vector<Vec3>* field : fields) {
          const Vec3& v = (*field)[static_cast<std::size_t>(start + k)];
          *o++ = v[0], *o++ = v[1], *o++ = v[2];
        }
      sums_in_[s].resize(ghost_send_[d][s].size() * 3 * f);
    }
    exchange_along_axis(comm(), {dec.neighbor(d, 0), dec.neighbor(d, 1)}, sums_out_, sums_in_, true,
                        kTagSums + 10 * d);
    for (int s = 0; s < 2; ++s) {
      const std::vector<int>& send = ghost_send_[d][s];
      const double* in = sums_in_[s].data();
      for (int i : send)
        for (std::vector<Vec3>* field : fields) {
          (*field)[static_cast<std::size_t>(i)] += Vec3(in[0], in[1], in[2]);
          in += 3;
        }
    }
  }
}

long Domain::owned_cost(const std::vector<int>& slots_per_owned, int n_owned, int i) const {
  if (balance_state_.cost == BalanceCost::particles) return 1;
  // The particle and its list slots (lists of the last build: the owned particles have not
  // changed since).
  if (slots_per_owned.size() != static_cast<std::size_t>(n_owned)) return 1;
  return 1 + slots_per_owned[static_cast<std::size_t>(i)];
}

// The load balance (docs/parallel.md, "Load balance"): at a rebuild, before migration, every
// rank bins the cost of its owned particles along each cut axis; one integer MPI_Allreduce
// sums the histograms (exact, so the same numbers on every rank whatever the reduction
// order), and every rank places the planes at the quantiles of the same histogram
// (quantile_cuts, clamp_cuts: load_balance.h). The planes are therefore bit for bit the same
// everywhere; they never enter the physics.
bool Domain::rebalance_if_due(const ParticleStore& p, const std::vector<int>& slots_per_owned, long step) {
  if (balance_state_.interval <= 0 || step < balance_state_.next_step) return false;
  balance_state_.next_step = step + balance_state_.interval;
  Decomposition& dec = *decomp_;
  const std::array<int, 3>& blocks = dec.blocks();
  const Box& box = dec.box();
  const int n_owned = static_cast<int>(p.size());
  const std::size_t n = 3 * static_cast<std::size_t>(kBalanceBins) + 1;
  balance_state_.histogram.assign(n, 0);
  balance_state_.reduced.assign(n, 0);
  long* h = balance_state_.histogram.data();
  long mine = 0;
  for (int i = 0; i < n_owned; ++i) {
    const long w = owned_cost(slots_per_owned, n_owned, i);
    mine += w;
    for (int d = 0; d < 3; ++d) {
      if (blocks[d] < 2) continue;
      h[d * kBalanceBins + balance_bin(p.x[i][d], box.lo[d], box.hi[d], kBalanceBins)] += w;
    }
  }
  h[n - 1] = mine;
  long max_cost = 0;
  timed([&] {
    MPI_Allreduce(h, balance_state_.reduced.data(), static_cast<int>(n), MPI_LONG, MPI_SUM, comm());
    MPI_Allreduce(&mine, &max_cost, 1, MPI_LONG, MPI_MAX, comm());
  });
  balance_.before = imbalance_ratio(max_cost, balance_state_.reduced[n - 1], dec.size());
  place_planes(balance_state_.reduced.data());
  ++balance_.count;
  balance_.last_step = step;
  balance_state_.measure_after = true;
  return true;
}

void Domain::measure_balance(int n_owned, const std::vector<int>& slots_per_owned) {
  if (!balance_state_.measure_after) return;
  balance_state_.measure_after = false;
  long mine = 0;
  for (int i = 0; i < n_owned; ++i) mine += owned_cost(slots_per_owned, n_owned, i);
  long max_cost = 0, total = 0;
  timed([&] {
    MPI_Allreduce(&mine, &max_cost, 1, MPI_LONG, MPI_MAX, comm());
    MPI_Allreduce(&mine, &total, 1, MPI_LONG, MPI_SUM, comm());
  });
  balance_.after = imbalance_ratio(max_cost, total, decomp_->size());
}

}  // namespace upgrain::dem
