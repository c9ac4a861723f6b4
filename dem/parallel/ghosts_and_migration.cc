// The communication of ParallelSimulation: migration and ghosts, both by the three-stage
// exchange (along x, then y, then z, each with the two face neighbours). Forwarding what
// arrived in earlier stages reaches the 12 edge and 8 corner neighbours without messages
// to them (Plimpton 1995, J. Comput. Phys. 117:1, sec. 4). After a load-balance move of
// the planes, migration repeats these stages until every particle is home.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <sstream>

#include "dem/parallel/exchange.h"
#include "dem/parallel/parallel_simulation.h"

namespace upgrain::dem {

namespace {

constexpr int kTagMigrate = 100;
constexpr int kTagSprings = 200;
constexpr int kTagGhosts = 300;
constexpr int kTagRefresh = 400;
constexpr int kTagShapes = 500;        // migration, next to kTagMigrate
constexpr int kTagMemory = 600;        // migration, next to kTagSprings
constexpr int kTagGhostShapes = 700;   // next to kTagGhosts
constexpr int kTagOrientations = 800;  // next to kTagRefresh

// The records of `history` that involve a particle of `leaving` (sorted), appended to out.
template <class R>
void records_of(const std::vector<R>& history, const std::vector<GlobalId>& leaving, std::vector<R>& out) {
  for (const R& r : history) {
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

void ParallelSimulation::migrate() {
  const Decomposition& dec = *decomp_;
  const std::array<int, 3>& me = dec.coords();
  // A particle may only move to an adjacent block between two rebuilds: farther, and the
  // ghosts it should have met were never here. Stop, naming it, rather than lose contacts.
  std::string message;
  for (int i = 0; i < n_owned_ && message.empty(); ++i) {
    const std::array<int, 3> c = dec.block_of(p_.x[i]);
    if (std::abs(c[0] - me[0]) > 1 || std::abs(c[1] - me[1]) > 1 || std::abs(c[2] - me[2]) > 1) {
      std::ostringstream m;
      m << "particle " << p_.id[i] << " at (" << p_.x[i][0] << ", " << p_.x[i][1] << ", " << p_.x[i][2]
        << ") m moved from block " << block_name(me) << " (rank " << dec.rank() << ") to block "
        << block_name(c) << ", farther than one block, by step " << step_ << " (t = " << step_ * dt_
        << " s); the time step is too large or the particle was ejected";
      message = m.str();
    }
  }
  std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  throw_if_any(comm_, message);
  timings_.rebuild_messages += seconds_since(t);

  // The check above used the planes the particles were last sorted by; a rebalance moves
  // them only now. A particle may then be several blocks from home: each pass moves it one
  // block along every axis, and a global reduction decides whether another pass is needed
  // (at most max(blocks) - 1 passes; the springs travel with it at every hop).
  if (!rebalance_if_due()) {
    migration_pass();
    return;
  }
  const std::array<int, 3>& b = dec.blocks();
  const int max_passes = std::max({b[0], b[1], b[2]});
  for (int pass = 1;; ++pass) {
    migration_pass();
    int away = 0;
    for (int i = 0; i < n_owned_ && away == 0; ++i) away = dec.block_of(p_.x[i]) == me ? 0 : 1;
    int any_away = 0;
    t = std::chrono::steady_clock::now();
    MPI_Allreduce(&away, &any_away, 1, MPI_INT, MPI_MAX, comm_);
    timings_.rebuild_messages += seconds_since(t);
    if (any_away == 0) return;
    // Collective: every rank sees the same any_away and pass.
    if (pass >= max_passes)
      throw Error("load balance: particles still away from their blocks after migration");
  }
}

void ParallelSimulation::migration_pass() {
  const Decomposition& dec = *decomp_;
  const std::array<int, 3>& me = dec.coords();
  std::chrono::steady_clock::time_point t;
  std::array<std::vector<GlobalId>, 2> leaving;
  for (int d = 0; d < 3; ++d) {
    for (int s = 0; s < 2; ++s) {
      state_out_[s].clear();
      spring_out_[s].clear();
      shape_out_[s].clear();
      memory_out_[s].clear();
      leaving[s].clear();
    }
    // Compact the owned particles in place, packing the leavers.
    int keep = 0;
    for (int i = 0; i < n_owned_; ++i) {
      const int c = dec.block_of(p_.x[i])[d];
      if (c != me[d]) {
        const int s = c < me[d] ? 0 : 1;
        const StateRecord r = pack_state(p_, static_cast<std::size_t>(i));
        state_out_[s].push_back(r);
        if (shapes_) shape_out_[s].push_back(pack_shape(p_, static_cast<std::size_t>(i)));
        leaving[s].push_back(r.gid);
        continue;
      }
      if (keep != i) copy_particle(p_, static_cast<std::size_t>(i), static_cast<std::size_t>(keep));
      ++keep;
    }
    truncate_store(p_, static_cast<std::size_t>(keep));
    n_owned_ = keep;
    // Every spring of a leaver goes with it (a copy stays: the partner may stay here).
    for (int s = 0; s < 2; ++s) {
      std::sort(leaving[s].begin(), leaving[s].end());
      if (leaving[s].empty()) continue;
      records_of(history_, leaving[s], spring_out_[s]);
      // Ellipsoids: the contact memories go with them the same way.
      if (shapes_) records_of(memory_history_, leaving[s], memory_out_[s]);
    }
    const std::array<int, 2> nb{dec.neighbor(d, 0), dec.neighbor(d, 1)};
    t = std::chrono::steady_clock::now();
    exchange_along_axis(comm_, nb, state_out_, state_in_, false, kTagMigrate + 10 * d);
    exchange_along_axis(comm_, nb, spring_out_, spring_in_, false, kTagSprings + 10 * d);
    if (shapes_) {
      exchange_along_axis(comm_, nb, shape_out_, shape_in_, false, kTagShapes + 10 * d);
      exchange_along_axis(comm_, nb, memory_out_, memory_in_, false, kTagMemory + 10 * d);
    }
    timings_.rebuild_messages += seconds_since(t);
    for (int s = 0; s < 2; ++s) {
      migrated_out_ += static_cast<long>(state_out_[s].size());
      for (const StateRecord& r : state_in_[s]) append_state(p_, r);
      history_.insert(history_.end(), spring_in_[s].begin(), spring_in_[s].end());
      if (shapes_) {
        for (const ShapeRecord& r : shape_in_[s]) append_shape(p_, r);
        memory_history_.insert(memory_history_.end(), memory_in_[s].begin(), memory_in_[s].end());
      }
    }
    n_owned_ = static_cast<int>(p_.size());
  }
}

void ParallelSimulation::build_ghosts() {
  const Decomposition& dec = *decomp_;
  const Box& block = dec.block();
  for (int d = 0; d < 3; ++d) {
    for (int s = 0; s < 2; ++s) {
      std::vector<int>& send = ghost_send_[d][s];
      send.clear();
      ghost_out_[s].clear();
      shape_out_[s].clear();
      if (dec.neighbor(d, s) == MPI_PROC_NULL) continue;
      // Everything within the interaction range of the face, ghosts of earlier stages
      // included (they cover the edges and corners).
      const double bound = s == 0 ? block.lo[d] + range_ : block.hi[d] - range_;
      const int n = static_cast<int>(p_.size());
      for (int i = 0; i < n; ++i) {
        if (s == 0 ? p_.x[i][d] < bound : p_.x[i][d] > bound) send.push_back(i);
      }
      for (int i : send) {
        GhostRecord r{};
        r.gid = p_.id[i];
        r.radius = p_.radius[i];
        r.inv_mass = p_.inv_mass[i];
        r.inv_inertia = p_.inv_inertia[i];
        put(r.x, p_.x[i]);
        put(r.v, p_.v[i]);
        put(r.omega, p_.omega[i]);
        ghost_out_[s].push_back(r);
        if (shapes_) shape_out_[s].push_back(pack_shape(p_, static_cast<std::size_t>(i)));
      }
    }
    const std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
    exchange_along_axis(comm_, {dec.neighbor(d, 0), dec.neighbor(d, 1)}, ghost_out_, ghost_in_, false,
                        kTagGhosts + 10 * d);
    if (shapes_)
      exchange_along_axis(comm_, {dec.neighbor(d, 0), dec.neighbor(d, 1)}, shape_out_, shape_in_, false,
                          kTagGhostShapes + 10 * d);
    timings_.rebuild_messages += seconds_since(t);
    for (int s = 0; s < 2; ++s) {
      ghost_recv_start_[d][s] = static_cast<int>(p_.size());
      ghost_recv_count_[d][s] = static_cast<int>(ghost_in_[s].size());
      for (const GhostRecord& r : ghost_in_[s]) {
        p_.id.push_back(r.gid);
        p_.radius.push_back(r.radius);
        p_.inv_mass.push_back(r.inv_mass);
        p_.inv_inertia.push_back(r.inv_inertia);
        p_.x.push_back(get(r.x));
        p_.v.push_back(get(r.v));
        p_.omega.push_back(get(r.omega));
        p_.force.push_back(Vec3::Zero());
        p_.torque.push_back(Vec3::Zero());
      }
      if (shapes_)
        for (const ShapeRecord& r : shape_in_[s]) append_shape(p_, r);
    }
  }
}

void ParallelSimulation::refresh_ghosts() {
  const Decomposition& dec = *decomp_;
  for (int d = 0; d < 3; ++d) {
    for (int s = 0; s < 2; ++s) {
      const std::vector<int>& send = ghost_send_[d][s];
      motion_out_[s].resize(send.size());
      for (std::size_t k = 0; k < send.size(); ++k) {
        MotionRecord& r = motion_out_[s][k];
        put(r.x, p_.x[send[k]]);
        put(r.v, p_.v[send[k]]);
        put(r.omega, p_.omega[send[k]]);
      }
      motion_in_[s].resize(static_cast<std::size_t>(ghost_recv_count_[d][s]));
      if (shapes_) {
        orientation_out_[s].resize(send.size());
        for (std::size_t k = 0; k < send.size(); ++k) put(orientation_out_[s][k].q, p_.orientation[send[k]]);
        orientation_in_[s].resize(static_cast<std::size_t>(ghost_recv_count_[d][s]));
      }
    }
    exchange_along_axis(comm_, {dec.neighbor(d, 0), dec.neighbor(d, 1)}, motion_out_, motion_in_, true,
                        kTagRefresh + 10 * d);
    if (shapes_)
      exchange_along_axis(comm_, {dec.neighbor(d, 0), dec.neighbor(d, 1)}, orientation_out_, orientation_in_,
                          true, kTagOrientations + 10 * d);
    for (int s = 0; s < 2; ++s) {
      const int start = ghost_recv_start_[d][s];
      for (std::size_t k = 0; k < motion_in_[s].size(); ++k) {
        const MotionRecord& r = motion_in_[s][k];
        const std::size_t i = static_cast<std::size_t>(start) + k;
        p_.x[i] = get(r.x);
        p_.v[i] = get(r.v);
        p_.omega[i] = get(r.omega);
      }
      if (shapes_)
        for (std::size_t k = 0; k < orientation_in_[s].size(); ++k)
          p_.orientation[static_cast<std::size_t>(start) + k] = get_quaternion(orientation_in_[s][k].q);
    }
  }
}

}  // namespace upgrain::dem
