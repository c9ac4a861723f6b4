#include "dem/parallel/parallel_simulation.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <sstream>
#include <utility>

#include "dem/core/error.h"
#include "dem/motion/grain_rotation.h"
#include "dem/neighbor/cell_grid.h"
#include "dem/parallel/exchange.h"
#include "dem/simulation.h"

namespace upgrain::dem {

namespace {

// In chunks below 2 GB (int counts).
template <class T>
void broadcast_records(std::vector<T>& all, MPI_Comm comm) {
  constexpr std::size_t kChunk = (1u << 30) / sizeof(T);
  for (std::size_t s = 0; s < all.size(); s += kChunk) {
    const std::size_t c = std::min(kChunk, all.size() - s);
    MPI_Bcast(all.data() + s, static_cast<int>(c * sizeof(T)), MPI_BYTE, 0, comm);
  }
}

// Rank 0's particles on every rank, so that every rank derives the same box and radii;
// their shapes in `shapes` (same order) when rank 0's store has them.
std::vector<StateRecord> broadcast_particles(const ParticleStore& p, MPI_Comm comm,
                                             std::vector<ShapeRecord>& shapes) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<StateRecord> all;
  long n[2] = {0, 0};  // count, has shapes
  if (rank == 0) {
    n[0] = static_cast<long>(p.size());
    n[1] = p.has_shapes() ? 1 : 0;
    all.reserve(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) all.push_back(pack_state(p, i));
    if (p.has_shapes())
      for (std::size_t i = 0; i < p.size(); ++i) shapes.push_back(pack_shape(p, i));
  }
  MPI_Bcast(n, 2, MPI_LONG, 0, comm);
  all.resize(static_cast<std::size_t>(n[0]));
  broadcast_records(all, comm);
  shapes.resize(n[1] != 0 ? all.size() : 0);
  broadcast_records(shapes, comm);
  return all;
}

Box default_box(const SceneConfig& scene, const std::vector<StateRecord>& all, double r_max) {
  Box b;
  double z_lo = 0.0, z_hi = 0.0;
  for (const StateRecord& r : all) {
    z_lo = std::min(z_lo, r.x[2] - r_max);
    z_hi = std::max(z_hi, r.x[2] + r_max);
  }
  b.lo = Vec3(0.0, 0.0, z_lo);
  b.hi = Vec3(scene.container.lx, scene.container.ly, z_hi);
  return b;
}

}  // namespace

ParallelSimulation::ParallelSimulation(const SceneConfig& scene, const ParticleStore& particles,
                                       MPI_Comm comm, const ParallelOptions& options)
    : ParallelSimulation(scene, particles, make_open_box(scene.container), comm, options) {}

ParallelSimulation::ParallelSimulation(const SceneConfig& scene, const ParticleStore& particles,
                                       std::vector<PlaneWall> walls, MPI_Comm comm,
                                       const ParallelOptions& options)
    : scene_(scene),
      walls_(std::move(walls)),
      g_(scene.effects.gravity ? Vec3(0, 0, -scene.gravity) : Vec3::Zero()),
      dt_(scene.time_step),
      rotation_(scene.effects.rotation && (scene.effects.friction || scene.effects.wall_friction)),
      kernels_(select_deterministic_forces(scene.effects)),
      energy_tracking_(scene.effects.energy_tracking),
      material_(ContactMaterial::from(scene.particles.material, scene.friction, scene.damping_ratio)) {
  if (scene.effects.rolling_resistance)
    throw Error(
        "the MPI DEM does not yet have rolling resistance: run scenes with Effects/rolling resistance on one "
        "rank (Parallel/DEM engine = serial)");
  if (!scene.effects.wall_friction) {
    for (auto& w : walls_) w.friction = 0.0;
  }
  std::vector<ShapeRecord> shapes;
  const std::vector<StateRecord> all = broadcast_particles(particles, comm, shapes);
  shapes_ = !shapes.empty();
  if (shapes_) {
    // As Simulation: ellipsoids turn under normal forces as well.
    rotation_ = scene.effects.rotation;
    kernels_ = select_deterministic_forces(scene.effects, true);
  }
  n_global_ = static_cast<long>(all.size());
  for (const StateRecord& r : all) max_radius_ = std::max(max_radius_, r.radius);
  // As Simulation: the skin in units of the largest diameter.
  skin_ = scene.neighbor_skin * 2.0 * max_radius_;
  max_radius_ = std::max(max_radius_, 1e-12);
  range_ = 2.0 * max_radius_ + skin_;
  const Box box = options.box ? *options.box : default_box(scene, all, max_radius_);
  decomp_ = std::make_unique<Decomposition>(comm, box, range_, options.blocks);
  if (options.balance_interval < 0) throw Error("load balance: balance_interval must be >= 0 steps");
  balance_.interval = options.balance_interval;
  balance_.cost = options.balance_cost;
  balance_.next_step = options.balance_at_start ? 0 : options.balance_interval;
  comm_ = decomp_->comm();
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (decomp_->owner_of(get(all[k].x)) != decomp_->rank()) continue;
    append_state(p_, all[k]);
    if (shapes_) append_shape(p_, shapes[k]);
  }
  n_owned_ = static_cast<int>(p_.size());
  rebuild();
  evaluate_forces();
  e0_ = energy();
  timings_ = {};  // step() only
}

void ParallelSimulation::step() {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  const int n = n_owned_;
  const double half = 0.5 * dt_;
  const double limit2 = 0.25 * skin_ * skin_;
  // Simulation::step, operation for operation: first half kick and drift with the
  // displacement check in the same pass, then the rotational half kick.
  bool moved = false;
  for (int i = 0; i < n; ++i) {
    p_.v[i] += half * (p_.force[i] * p_.inv_mass[i] + g_);
    p_.x[i] += dt_ * p_.v[i];
    moved = moved || (p_.x[i] - x_at_build_[i]).squaredNorm() > limit2;
  }
  if (rotation_) {
    if (shapes_)
      rotation_first_half(p_, static_cast<std::size_t>(n), half, dt_);
    else
      for (int i = 0; i < n; ++i) p_.omega[i] += half * p_.inv_inertia[i] * p_.torque[i];
  }
  // Second half of the work of the previous step's damping forces, with v(k+1/2), as
  // Simulation::step (the owned particles are still those of that evaluation).
  if (!energy_terms_.damping_force.empty()) {
    double work = 0.0;
    for (int i = 0; i < n; ++i) work += energy_terms_.damping_force[i].dot(p_.v[i]);
    // Ellipsoids: the damping force misses the centroid and works on the rotation too.
    for (std::size_t i = 0; i < energy_terms_.damping_torque.size(); ++i)
      work += energy_terms_.damping_torque[i].dot(p_.omega[i]);
    dissipated_damping_ -= half * work;
  }
  // One reduction per step carries both global decisions: rebuild now (every rank at the
  // same steps), and the runaway-overlap check of the previous evaluation.
  double local[2] = {moved ? 1.0 : 0.0, last_overlap_ratio_};
  double global[2] = {0.0, 0.0};
  const Clock::time_point t1 = Clock::now();
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, comm_);
  const Clock::time_point t2 = Clock::now();
  if (global[1] > kRunawayOverlapRatio) {
    std::ostringstream m;
    m << "runaway overlap at step " << last_overlap_step_ << " (t = " << last_overlap_step_ * dt_
      << " s): an overlap reached " << global[1] << " of a radius (limit " << kRunawayOverlapRatio
      << "); the time step " << dt_
      << " s is too large for this scene or a particle was placed inside another";
    throw Error(m.str());
  }
  const bool rebuilding = global[0] > 0.0;
  if (rebuilding)
    rebuild();
  else
    refresh_ghosts();
  const Clock::time_point t3 = Clock::now();
  evaluate_forces();
  const Clock::time_point t4 = Clock::now();
  for (int i = 0; i < n_owned_; ++i) p_.v[i] += half * (p_.force[i] * p_.inv_mass[i] + g_);
  if (rotation_) {
    if (shapes_)
      rotation_second_half(p_, static_cast<std::size_t>(n_owned_), half);
    else
      for (int i = 0; i < n_owned_; ++i) p_.omega[i] += half * p_.inv_inertia[i] * p_.torque[i];
  }
  ++step_;
  const Clock::time_point t5 = Clock::now();
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  timings_.integrate += seconds(t0, t1) + seconds(t4, t5);
  timings_.reduction += seconds(t1, t2);
  (rebuilding ? timings_.rebuild : timings_.ghost_refresh) += seconds(t2, t3);
  timings_.forces += seconds(t3, t4);
  ++timings_.steps;
}

void ParallelSimulation::run(long steps) {
  for (long s = 0; s < steps; ++s) step();
}

void ParallelSimulation::rebuild() {
  std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  check_finite();
  timings_.rebuild_messages += seconds_since(t);
  // Springs of touching contacts, keyed by global ids, before local indices change.
  history_.clear();
  lists_.collect_springs(p_, history_);
  memory_history_.clear();
  if (shapes_) lists_.collect_memory(p_, memory_history_);
  // Drop the ghosts; they are rebuilt below from the new owners.
  truncate_store(p_, static_cast<std::size_t>(n_owned_));
  migrate();
  long count = n_owned_;
  long total = 0;
  t = std::chrono::steady_clock::now();
  MPI_Allreduce(&count, &total, 1, MPI_LONG, MPI_SUM, comm_);
  timings_.rebuild_messages += seconds_since(t);
  if (total != n_global_) {
    std::ostringstream m;
    m << "parallel run: " << total << " particles after the migration at step " << step_ << ", expected "
      << n_global_;
    throw Error(m.str());
  }
  // A pair straddling two ranks arrives with its spring from both: the copies are equal.
  std::sort(history_.begin(), history_.end());
  history_.erase(std::unique(history_.begin(), history_.end(),
                             [](const SpringRecord& a, const SpringRecord& b) { return a.same_key(b); }),
                 history_.end());
  // The same for the contact memories: a straddling pair is evaluated on both ranks from
  // the same inputs, in the same orientation (lo as body i).
  std::sort(memory_history_.begin(), memory_history_.end());
  memory_history_.erase(
      std::unique(memory_history_.begin(), memory_history_.end(),
                  [](const MemoryRecord& a, const MemoryRecord& b) { return a.same_key(b); }),
      memory_history_.end());
  sort_owned_by_cell();
  build_ghosts();
  lists_.build(p_, n_owned_, max_radius_, skin_, walls_, history_, shapes_ ? &memory_history_ : nullptr);
  x_at_build_.assign(p_.x.begin(), p_.x.begin() + n_owned_);
  ++rebuilds_;
  if (balance_.measure_after) measure_balance_after();
}

// Memory locality only (as VerletList::rebuild): no result depends on the local order,
// since every sum runs in global-id order.
void ParallelSimulation::sort_owned_by_cell() {
  if (n_owned_ == 0) return;
  Vec3 lo = p_.x[0], hi = p_.x[0];
  for (int i = 1; i < n_owned_; ++i) {
    lo = lo.cwiseMin(p_.x[i]);
    hi = hi.cwiseMax(p_.x[i]);
  }
  CellGrid grid(lo, hi, range_, 4L * n_owned_ + 64);
  grid.bin(p_.x);
  p_.permute(grid.order());
}

void ParallelSimulation::evaluate_forces() {
  DeterministicForceInput in;
  in.particles = &p_;
  in.n_owned = n_owned_;
  in.lists = &lists_;
  in.walls = &walls_;
  in.material = material_;
  in.dt = dt_;
  in.energy = &energy_terms_;
  in.record = &contacts_;
  in.posed = &posed_;
  in.solver_stats = &solver_stats_;
  recorded_ = record_next_;
  if (!record_next_) contacts_.clear();
  const DeterministicForceResult r = record_next_ ? kernels_.recording(in) : kernels_.plain(in);
  record_next_ = false;
  dissipated_damping_ += r.dissipated.dissipated_damping;
  dissipated_friction_ += r.dissipated.dissipated_friction;
  stiffness_change_ += r.dissipated.tangential_stiffness_change;
  last_overlap_ratio_ = r.max_overlap_ratio;
  last_overlap_step_ = step_;
  last_pair_contacts_ = r.pair_contacts;
  last_wall_contacts_ = r.wall_contacts;
}

StepDiagnostics ParallelSimulation::step_diagnostics() const {
  long counts[2] = {last_pair_contacts_, last_wall_contacts_};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG, MPI_SUM, comm_);
  double overlap = last_overlap_ratio_;
  MPI_Allreduce(MPI_IN_PLACE, &overlap, 1, MPI_DOUBLE, MPI_MAX, comm_);
  StepDiagnostics d;
  d.particle_contacts = counts[0];
  d.wall_contacts = counts[1];
  d.max_overlap_ratio = overlap;
  d.neighbor_builds = rebuilds_;
  // Summed over ranks: a pair straddling two ranks is solved on both, so the counts exceed
  // those of one rank (diagnostics only).
  const ContactSolverStats& s = solver_stats_;
  std::int64_t c[9] = {s.calls,    s.warm_starts, s.warm_rejected, s.newton_iterations, s.fallbacks,
                       s.failures, s.uncertified, s.proven_apart,  s.still_apart};
  MPI_Allreduce(MPI_IN_PLACE, c, 9, MPI_INT64_T, MPI_SUM, comm_);
  d.contact_solver.calls = c[0];
  d.contact_solver.warm_starts = c[1];
  d.contact_solver.warm_rejected = c[2];
  d.contact_solver.newton_iterations = c[3];
  d.contact_solver.fallbacks = c[4];
  d.contact_solver.failures = c[5];
  d.contact_solver.uncertified = c[6];
  d.contact_solver.proven_apart = c[7];
  d.contact_solver.still_apart = c[8];
  return d;
}

void ParallelSimulation::remove_wall(const std::string& name) {
  for (PlaneWall& w : walls_) {
    if (w.name != name) continue;
    w.point -= 1e100 * w.normal;  // as Simulation::remove_wall
    rebuild();
    return;
  }
  throw Error("no wall named '" + name + "' to remove");
}

void ParallelSimulation::check_finite() const {
  std::string message;
  for (int i = 0; i < n_owned_; ++i) {
    const bool orientation_ok = !shapes_ || p_.orientation[i].coeffs().allFinite();
    if (!p_.x[i].allFinite() || !p_.v[i].allFinite() || !p_.omega[i].allFinite() || !orientation_ok) {
      std::ostringstream m;
      m << "particle " << p_.id[i] << " has a non-finite position, velocity or orientation at step " << step_
        << " (t = " << step_ * dt_ << " s)";
      message = m.str();
      break;
    }
  }
  throw_if_any(comm_, message);
}

ParticleStore ParallelSimulation::gather_sorted_by_id() const {
  if (shapes_) {
    struct Shaped {
      StateRecord state;
      ShapeRecord shape;
    };
    std::vector<Shaped> mine;
    mine.reserve(static_cast<std::size_t>(n_owned_));
    for (int i = 0; i < n_owned_; ++i)
      mine.push_back(
          {pack_state(p_, static_cast<std::size_t>(i)), pack_shape(p_, static_cast<std::size_t>(i))});
    std::vector<Shaped> all = gather_to_root(mine, comm_);
    std::sort(all.begin(), all.end(),
              [](const Shaped& a, const Shaped& b) { return a.state.gid < b.state.gid; });
    ParticleStore out;
    out.reserve(all.size());
    for (const Shaped& r : all) {
      append_state(out, r.state);
      append_shape(out, r.shape);
    }
    return out;
  }
  std::vector<StateRecord> mine;
  mine.reserve(static_cast<std::size_t>(n_owned_));
  for (int i = 0; i < n_owned_; ++i) mine.push_back(pack_state(p_, static_cast<std::size_t>(i)));
  const int bytes = static_cast<int>(mine.size() * sizeof(StateRecord));
  const int rank = decomp_->rank();
  const int size = decomp_->size();
  std::vector<int> counts(rank == 0 ? size : 0), displs(rank == 0 ? size : 0);
  MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  std::vector<StateRecord> all;
  if (rank == 0) {
    long total = 0;
    for (int r = 0; r < size; ++r) {
      displs[r] = static_cast<int>(total);
      total += counts[r];
    }
    all.resize(static_cast<std::size_t>(total) / sizeof(StateRecord));
  }
  MPI_Gatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, 0, comm_);
  std::sort(all.begin(), all.end(), [](const StateRecord& a, const StateRecord& b) { return a.gid < b.gid; });
  ParticleStore out;
  out.reserve(all.size());
  for (const StateRecord& r : all) append_state(out, r);
  return out;
}

GridStress ParallelSimulation::grid_stress(const RegularGrid& grid) const {
  if (!recorded_)
    throw Error("parallel grid stress: no contacts recorded at the last step (request_contacts())");
  return parallel_grid_stress(p_, n_owned_, contacts_, grid, grain_dynamics(), comm_);
}

std::vector<int> ParallelSimulation::gather_owners_sorted_by_id() const {
  struct Owned {
    GlobalId gid;
    int rank;
  };
  std::vector<Owned> mine(static_cast<std::size_t>(n_owned_));
  for (int i = 0; i < n_owned_; ++i) mine[static_cast<std::size_t>(i)] = {p_.id[i], decomp_->rank()};
  std::vector<Owned> all = gather_to_root(mine, comm_);
  std::sort(all.begin(), all.end(), [](const Owned& a, const Owned& b) { return a.gid < b.gid; });
  std::vector<int> owner(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) owner[k] = all[k].rank;
  return owner;
}

std::vector<Box> ParallelSimulation::compute_grid_blocks() const {
  return dem::compute_grid_blocks(*decomp_);
}

ComputeGridStress ParallelSimulation::compute_grid_stress() const {
  if (!recorded_)
    throw Error("parallel grid stress: no contacts recorded at the last step (request_contacts())");
  return parallel_compute_grid_stress(p_, n_owned_, contacts_, *decomp_, grain_dynamics());
}

std::vector<ContactRecord> ParallelSimulation::gather_contacts_by_id() const {
  if (!recorded_) throw Error("parallel contacts: none recorded at the last step (request_contacts())");
  std::vector<ContactRecord> mine;
  for (const ContactSample& c : contacts_) {
    // Walls belong to owned particles; a pair is sent by the owner of its lower id.
    if (!c.with_wall() && c.a >= n_owned_) continue;
    ContactRecord r{p_.id[c.a], c.with_wall() ? -1 - static_cast<GlobalId>(c.wall()) : p_.id[c.b], {}, {}};
    put(r.point, c.point);
    put(r.force, c.force_on_a);
    mine.push_back(r);
  }
  std::vector<ContactRecord> all = gather_to_root(mine, comm_);
  std::sort(all.begin(), all.end());
  return all;
}

std::vector<ContactSample> contacts_in_store(const std::vector<ContactRecord>& contacts,
                                             const ParticleStore& sorted) {
  auto index = [&](GlobalId gid) {
    const auto it = std::lower_bound(sorted.id.begin(), sorted.id.end(), gid);
    if (it == sorted.id.end() || *it != gid) throw Error("contacts_in_store: particle not in the store");
    return static_cast<int>(it - sorted.id.begin());
  };
  std::vector<ContactSample> out;
  out.reserve(contacts.size());
  for (const ContactRecord& r : contacts)
    out.push_back({index(r.a), r.b < 0 ? static_cast<int>(r.b) : index(r.b), get(r.point), get(r.force)});
  return out;
}

EnergyBalance ParallelSimulation::energy() const {
  struct Record {
    GlobalId gid;
    double e[5];  // kinetic translational, rotational, potential, elastic normal, tangential
  };
  const bool elastic = !energy_terms_.elastic_normal.empty();
  std::vector<Record> mine(static_cast<std::size_t>(n_owned_));
  for (int i = 0; i < n_owned_; ++i) {
    const double m = p_.mass(static_cast<std::size_t>(i));
    Record& r = mine[i];
    r.gid = p_.id[i];
    r.e[0] = 0.5 * m * p_.v[i].squaredNorm();
    r.e[1] = !rotation_ ? 0.0
             : shapes_  ? p_.rotational_energy(static_cast<std::size_t>(i))
                        : 0.5 * p_.omega[i].squaredNorm() / p_.inv_inertia[i];
    r.e[2] = -m * g_.dot(p_.x[i]);
    r.e[3] = elastic ? energy_terms_.elastic_normal[i] : 0.0;
    r.e[4] = elastic ? energy_terms_.elastic_tangential[i] : 0.0;
  }
  std::vector<Record> all = gather_to_root(mine, comm_);
  std::sort(all.begin(), all.end(), [](const Record& a, const Record& b) { return a.gid < b.gid; });
  double sums[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (const Record& r : all)
    for (int k = 0; k < 5; ++k) sums[k] += r.e[k];
  const double local[3] = {dissipated_damping_, dissipated_friction_, stiffness_change_};
  MPI_Reduce(local, sums + 5, 3, MPI_DOUBLE, MPI_SUM, 0, comm_);
  MPI_Bcast(sums, 8, MPI_DOUBLE, 0, comm_);
  EnergyBalance e;
  e.kinetic_translational = sums[0];
  e.kinetic_rotational = sums[1];
  e.potential = sums[2];
  e.elastic_normal = sums[3];
  e.elastic_tangential = sums[4];
  e.dissipated_damping = sums[5];
  e.dissipated_friction = sums[6];
  e.tangential_stiffness_change = sums[7];
  e.removed_by_relaxation = removed_by_relaxation_;
  return e;
}

std::vector<Vec3> ParallelSimulation::wall_forces() const {
  struct Record {
    long wall;
    GlobalId gid;
    double f[3];
  };
  std::vector<Record> mine;
  for (std::size_t e = 0; e < lists_.wall.size(); ++e) {
    const Vec3& f = lists_.wall_force_on_particle[e];
    if (f == Vec3::Zero()) continue;
    Record r{lists_.wall[e].wall, p_.id[lists_.wall[e].particle], {}};
    put(r.f, f);
    mine.push_back(r);
  }
  std::vector<Record> all = gather_to_root(mine, comm_);
  std::sort(all.begin(), all.end(), [](const Record& a, const Record& b) {
    return a.wall < b.wall || (a.wall == b.wall && a.gid < b.gid);
  });
  std::vector<double> total(3 * walls_.size(), 0.0);
  for (const Record& r : all)
    for (int d = 0; d < 3; ++d) total[3 * r.wall + d] -= r.f[d];
  MPI_Bcast(total.data(), static_cast<int>(total.size()), MPI_DOUBLE, 0, comm_);
  std::vector<Vec3> out(walls_.size());
  for (std::size_t w = 0; w < walls_.size(); ++w)
    out[w] = Vec3(total[3 * w], total[3 * w + 1], total[3 * w + 2]);
  return out;
}

ParallelDiagnostics ParallelSimulation::diagnostics() const {
  ParallelDiagnostics d;
  d.particles = n_global_;
  d.owned = n_owned_;
  d.ghosts = static_cast<long>(p_.size()) - n_owned_;
  d.pair_slots = static_cast<long>(lists_.num_pairs());
  d.rebuilds = rebuilds_;
  d.migrated_out = migrated_out_;
  d.max_overlap_ratio = last_overlap_ratio_;
  d.rebalances = balance_.count;
  d.rebalance_step = balance_.last_step;
  d.imbalance_before = balance_.before;
  d.imbalance_after = balance_.after;
  return d;
}

LoadImbalance ParallelSimulation::load_imbalance() const {
  const double mine[3] = {static_cast<double>(n_owned_), static_cast<double>(lists_.num_pairs()),
                          timings_.compute()};
  double max[3] = {0, 0, 0}, sum[3] = {0, 0, 0};
  MPI_Allreduce(mine, max, 3, MPI_DOUBLE, MPI_MAX, comm_);
  MPI_Allreduce(mine, sum, 3, MPI_DOUBLE, MPI_SUM, comm_);
  LoadImbalance b;
  b.ranks = decomp_->size();
  const double k = static_cast<double>(b.ranks);
  auto ratio = [](double hi, double mean) { return mean > 0.0 ? hi / mean : 1.0; };
  b.owned_max = static_cast<long>(max[0]);
  b.owned_mean = sum[0] / k;
  b.owned_ratio = ratio(max[0], b.owned_mean);
  b.pairs_max = static_cast<long>(max[1]);
  b.pairs_mean = sum[1] / k;
  b.pairs_ratio = ratio(max[1], b.pairs_mean);
  b.compute_max = max[2];
  b.compute_mean = sum[2] / k;
  b.compute_ratio = ratio(max[2], b.compute_mean);
  return b;
}

}  // namespace upgrain::dem
