// Capture and restore of the engine's state between two steps (engine_state.h,
// docs/restart.md).
#include <algorithm>

#include "dem/contact/contact_laws.h"
#include "dem/core/error.h"
#include "dem/core/out_of_memory.h"
#include "dem/engine/simulation.h"
#include "dem/engine/wall_columns.h"
#include "dem/parallel/byte_stream.h"
#include "dem/parallel/exchange.h"

namespace upgrain::dem {

namespace {

// What a particle carries into a checkpoint besides its state and shape.
struct ResumeRecord {
  GlobalId gid;
  double x_built[3];
  double damping_force[3], damping_torque[3], rolling_damping_torque[3];
  ElasticEnergy elastic;
  DissipatedEnergy dissipated;
};
struct ParticleRecord {
  StateRecord state;
  ShapeRecord shape;
  ResumeRecord resume;
};

// Which optional per-particle parts a state holds.
struct Parts {
  bool shapes = false, damping_force = false, damping_torque = false, rolling = false, energy = false;
};

Parts parts_of(const EngineState& s) {
  return {s.particles.has_shapes(), !s.damping_force.empty(), !s.damping_torque.empty(),
          !s.rolling_damping_torque.empty(), !s.particle_elastic.empty()};
}

// Grain i's record.
ParticleRecord particle_record(const EngineState& s, const Parts& parts, std::size_t i) {
  ParticleRecord r{};
  r.state = pack_state(s.particles, i);
  if (parts.shapes) r.shape = pack_shape(s.particles, i);
  r.resume.gid = s.particles.id[i];
  put(r.resume.x_built, s.positions_at_build[i]);
  if (parts.damping_force) put(r.resume.damping_force, s.damping_force[i]);
  if (parts.damping_torque) put(r.resume.damping_torque, s.damping_torque[i]);
  if (parts.rolling) put(r.resume.rolling_damping_torque, s.rolling_damping_torque[i]);
  if (parts.energy) {
    r.resume.elastic = s.particle_elastic[i];
    r.resume.dissipated = s.dissipation_share[i];
  }
  return r;
}

// Rank 0's `count` items handed out to the ranks in rounds of at most 64 MB of records, each
// round's records made as it goes (`make(k, out)` appends item k's, on rank 0), so that rank 0
// never holds a second copy of them all: what this rank received, in rank 0's order.
// `count` is known on every rank. Collective.
template <class T, class Make, class Destination>
std::vector<T> hand_out(long count, MPI_Comm comm, Make make, Destination destination) {
  constexpr long kPerRound = static_cast<long>((std::size_t{1} << 26) / sizeof(T));
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<T> received, part;
  for (long first = 0; first < count; first += kPerRound) {
    part.clear();
    if (rank == 0)
      for (long k = first; k < std::min(count, first + kPerRound); ++k)
        make(static_cast<std::size_t>(k), part);
    const std::vector<T> got = send_to_ranks(part, comm, destination);
    received.insert(received.end(), got.begin(), got.end());
  }
  return received;
}

// One grain's record appended to a state, with the parts the state carries.
void append_record(EngineState& s, const Parts& parts, const ParticleRecord& p) {
  append_state(s.particles, p.state);
  if (parts.shapes) append_shape(s.particles, p.shape);
  s.positions_at_build.push_back(get(p.resume.x_built));
  if (parts.damping_force) s.damping_force.push_back(get(p.resume.damping_force));
  if (parts.damping_torque) s.damping_torque.push_back(get(p.resume.damping_torque));
  if (parts.rolling) s.rolling_damping_torque.push_back(get(p.resume.rolling_damping_torque));
  if (parts.energy) {
    s.particle_elastic.push_back(p.resume.elastic);
    s.dissipation_share.push_back(p.resume.dissipated);
  }
}

// The parts of a state that are not per grain or per contact: the same on every rank.
void put_globals(ByteWriter& w, const EngineState& s) {
  const WallColumns walls = wall_columns(s);
  WallColumns::each(walls, [&](const char*, const auto& column) {
    w.put(static_cast<std::uint64_t>(column.size()));
    for (const auto& x : column) w.put(x);
  });
  w.put(s.pair_contacts);
  w.put(s.wall_contacts);
  w.put(static_cast<std::uint64_t>(s.wall_forces.size()));
  for (const Vec3& f : s.wall_forces) w.put(f);
  for (const Vec3& f : s.wall_damping_forces) w.put(f);
  w.put(s.step);
  w.put(s.rebuilds);
  w.put(s.rebuild_pending);
  w.put(s.last_overlap_ratio);
  w.put(s.last_overlap_step);
  w.put(s.gravity);
  w.put(s.initial_energy);
  w.put(s.removed_by_relaxation);
  w.put(s.dissipated);
  w.put(s.solver_stats);
  w.put(s.reference_mass);
  w.put(s.domain.box);
  w.put(s.domain.periodic);
  w.put(s.domain.blocks);
  for (const std::vector<double>& p : s.domain.planes) w.put(p);
  w.put(s.domain.balance);
  w.put(s.domain.next_balance_step);
  w.put(s.cell.values());
  if (s.cell.deforming) w.put(s.cell.shear_values());
}

void get_globals(ByteReader& r, EngineState& s) {
  WallColumns walls;
  WallColumns::each(walls, [&](const char*, auto& column) {
    std::uint64_t n = 0;
    r.get(n);
    column.resize(n);
    for (auto& x : column) r.get(x);
  });
  set_walls(s, std::move(walls), "restore: ");
  r.get(s.pair_contacts);
  r.get(s.wall_contacts);
  std::uint64_t forces = 0;
  r.get(forces);
  s.wall_forces.resize(forces);
  for (Vec3& f : s.wall_forces) r.get(f);
  s.wall_damping_forces.resize(forces);
  for (Vec3& f : s.wall_damping_forces) r.get(f);
  r.get(s.step);
  r.get(s.rebuilds);
  r.get(s.rebuild_pending);
  r.get(s.last_overlap_ratio);
  r.get(s.last_overlap_step);
  r.get(s.gravity);
  r.get(s.initial_energy);
  r.get(s.removed_by_relaxation);
  r.get(s.dissipated);
  r.get(s.solver_stats);
  r.get(s.reference_mass);
  r.get(s.domain.box);
  r.get(s.domain.periodic);
  r.get(s.domain.blocks);
  for (std::vector<double>& p : s.domain.planes) r.get(p);
  r.get(s.domain.balance);
  r.get(s.domain.next_balance_step);
  std::array<double, CellRecord::kValues> cell{};
  r.get(cell);
  s.cell = CellRecord::from_values(cell);
  if (s.cell.deforming) {
    std::array<double, CellRecord::kShearValues> shear{};
    r.get(shear);
    s.cell.set_shear_values(shear);
  }
}

}  // namespace

// The whole state as bytes and back (a DEM cell of FEM x DEM moved or kept as one block).
std::vector<char> to_bytes(const EngineState& s) {
  ByteWriter w;
  const Parts parts = parts_of(s);
  w.put(parts);
  std::vector<ParticleRecord> records(s.particles.size());
  for (std::size_t i = 0; i < records.size(); ++i) records[i] = particle_record(s, parts, i);
  w.put(records);
  w.put(s.history);
  put_globals(w, s);
  return std::move(w.bytes());
}

EngineState from_bytes(const std::vector<char>& bytes) {
  ByteReader r(bytes);
  EngineState s;
  Parts parts;
  r.get(parts);
  std::vector<ParticleRecord> records;
  r.get(records);
  s.particles.reserve(records.size());
  for (const ParticleRecord& p : records) append_record(s, parts, p);
  r.get(s.history);
  get_globals(r, s);
  return s;
}

namespace {

// The index of global id `gid` in a store sorted by id.
std::size_t index_of(const ParticleStore& sorted, GlobalId gid) {
  const auto it = std::lower_bound(sorted.id.begin(), sorted.id.end(), gid);
  if (it == sorted.id.end() || *it != gid)
    throw Error("restore: particle " + std::to_string(gid) + " is not in the state");
  return static_cast<std::size_t>(it - sorted.id.begin());
}

}  // namespace

EngineState Simulation::capture_state() const {
  // Between two steps, never between an insertion and the step that joins it (insert()).
  if (arrivals_pending_) throw Error("capture_state: grains inserted and not yet stepped");
  EngineState s;
  // Per particle, gathered by id.
  const std::vector<Vec3>& x_built = lists_->positions_at_build();
  std::vector<ParticleRecord> mine(static_cast<std::size_t>(n_owned_));
  const Parts parts{shapes_, !out_.damping_force.empty(), !out_.damping_torque.empty(),
                    !out_.rolling_damping_torque.empty(), !out_.particle_elastic.empty()};
  for (int i = 0; i < n_owned_; ++i) {
    ParticleRecord& r = mine[static_cast<std::size_t>(i)];
    r = ParticleRecord{};
    r.state = pack_state(p_, static_cast<std::size_t>(i));
    if (parts.shapes) r.shape = pack_shape(p_, static_cast<std::size_t>(i));
    r.resume.gid = p_.id[i];
    put(r.resume.x_built, x_built[i]);
    if (parts.damping_force) put(r.resume.damping_force, out_.damping_force[i]);
    if (parts.damping_torque) put(r.resume.damping_torque, out_.damping_torque[i]);
    if (parts.rolling) put(r.resume.rolling_damping_torque, out_.rolling_damping_torque[i]);
    if (parts.energy) {
      r.resume.elastic = out_.particle_elastic[i];
      r.resume.dissipated = dissipation_share_[static_cast<std::size_t>(i)];
    }
  }
  std::vector<ParticleRecord> all = gather_to_root(mine, comm());
  std::sort(all.begin(), all.end(),
            [](const ParticleRecord& a, const ParticleRecord& b) { return a.state.gid < b.state.gid; });
  // Every history with its separation budget: the restored lists hold the same pairs, and the
  // grains keep their motion bounds across the restart (the poses are primed from this state).
  std::vector<ContactHistoryRecord> records;
  history_.collect(lists_->pairs(), lists_->walls(), p_.id, true, records);
  std::vector<ContactHistoryRecord> history = gather_to_root(records, comm());
  // Collective parts before rank 0 fills the state.
  std::array<ExactSum, kChannels> dissipated;
  for (int c = 0; c < kChannels; ++c) dissipated[c] = dissipated_[c].reduced(comm());
  long contacts[2] = {out_.pair_contacts, out_.wall_contacts};
  MPI_Allreduce(MPI_IN_PLACE, contacts, 2, MPI_LONG, MPI_SUM, comm());
  double overlap = last_overlap_ratio_;
  MPI_Allreduce(MPI_IN_PLACE, &overlap, 1, MPI_DOUBLE, MPI_MAX, comm());
  WallLoads loads = wall_loads();
  ContactSolverStats stats = solver_stats_;
  static_assert(sizeof(ContactSolverStats) % sizeof(std::int64_t) == 0);
  static_assert(kChannels == EngineState::kDissipationChannels);
  MPI_Allreduce(MPI_IN_PLACE, &stats, static_cast<int>(sizeof(stats) / sizeof(std::int64_t)), MPI_INT64_T,
                MPI_SUM, comm());
  if (!is_root()) return s;
  s.particles.reserve(all.size());
  for (const ParticleRecord& r : all) append_record(s, parts, r);
  sort_unique(history);
  s.history = std::move(history);
  s.walls = walls_;
  s.wall_points_at_build = wall_points_at_build_;
  s.step = step_;
  s.rebuilds = rebuilds_;
  s.rebuild_pending = rebuild_pending_;
  s.last_overlap_ratio = overlap;
  s.pair_contacts = contacts[0];
  s.wall_contacts = contacts[1];
  s.wall_forces = std::move(loads.force);
  s.wall_damping_forces = std::move(loads.damping);
  s.last_overlap_step = last_overlap_step_;
  s.gravity = g_;
  s.initial_energy = e0_;
  s.removed_by_relaxation = removed_by_relaxation_;
  for (int c = 0; c < kChannels; ++c) s.dissipated[c] = dissipated[c].state();
  s.solver_stats = stats;
  s.reference_mass = reference_mass_;
  s.domain = domain_->state();
  if (deforming_) {
    s.cell.deforming = true;
    s.cell.start = cell_start_;
    s.cell.at_build = cell_at_build_;
    s.cell.velocity_gradient = cell_l_;
    s.cell.stress = cell_stress_;
    s.cell.stress_volume = cell_stress_volume_;
    s.cell.stress_known = cell_stress_known_;
    s.cell.work = cell_work_;
    s.cell.shear = domain_->decomposition().cell().shear;
    s.cell.offset_at_build = offset_at_build_;
  }
  return s;
}

Simulation::Simulation(const SceneConfig& scene, const EngineState& state_on_root, MPI_Comm comm,
                       const EngineOptions& options) try
    : scene_(scene),
      summation_(options.summation),
      dt_(scene.time_step),
      material_{scene.friction, scene.damping_ratio},
      law_constants_(
          find_contact_law(scene.contact_law).constants(scene.particles.material, scene.law_parameters)),
      rolling_(rolling_parameters(scene.rolling_friction, scene.rolling_damping_ratio,
                                  scene.effects.twisting_resistance, scene.particles.material.youngs_modulus,
                                  scene.particles.material.poisson_ratio)) {
  // Every rank takes the state's global part from rank 0 (broadcast), and later only its
  // block's grains and their histories, which rank 0 sends it: no other rank holds the whole
  // state, even for a moment.
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  struct Grains {
    long count = 0;
    long histories = 0;
    double max_radius = 0.0;
    Parts parts;
  } grains;
  std::vector<char> bytes;
  if (rank == 0) {
    grains.count = static_cast<long>(state_on_root.particles.size());
    grains.histories = static_cast<long>(state_on_root.history.size());
    for (double r : state_on_root.particles.radius) grains.max_radius = std::max(grains.max_radius, r);
    grains.parts = parts_of(state_on_root);
    ByteWriter w;
    put_globals(w, state_on_root);
    bytes = std::move(w.bytes());
  }
  MPI_Bcast(&grains, sizeof grains, MPI_BYTE, 0, comm);
  broadcast_bytes(bytes, comm);
  EngineState s;
  {
    ByteReader r(bytes);
    get_globals(r, s);
  }
  bytes = {};
  // A pour may start from an empty container (docs/insertion.md).
  if (grains.count == 0 && !scene.insertion.enabled()) throw Error("restore: the state holds no particles");
  walls_ = s.walls;
  note_wall_motion();
  if (s.wall_points_at_build.size() != walls_.size())
    throw Error("restore: " + std::to_string(s.wall_points_at_build.size()) + " wall points at build for " +
                std::to_string(walls_.size()) + " walls");
  wall_points_at_build_ = s.wall_points_at_build;
  g_ = s.gravity;
  EngineOptions o = options;
  // A deforming cell's grid is sized from its first box, and the decomposition then follows it
  // to the present one.
  o.box = s.cell.deforming ? s.cell.start : s.domain.box;
  o.balance_at_start = false;
  set_up(grains.count, grains.max_radius, grains.parts.shapes, *o.box, comm, o);
  if (domain_->decomposition().cell().periodic != s.domain.periodic) {
    auto axes = [](const std::array<bool, 3>& p) {
      std::string a;
      for (int d = 0; d < 3; ++d)
        if (p[d]) a += "xyz"[d];
      return a.empty() ? std::string("none") : a;
    };
    throw Error("restore: the state's periodic axes (" + axes(s.domain.periodic) + ") are not the scene's (" +
                axes(domain_->decomposition().cell().periodic) + ")");
  }
  if (deforming_ != s.cell.deforming)
    throw Error(std::string("restore: the scene's cell ") + (deforming_ ? "deforms" : "does not deform") +
                " (Cell), the state's " + (s.cell.deforming ? "does" : "does not"));
  if (deforming_) domain_->deform_cell(s.domain.box);
  if (s.cell.shear.any() != scene.cell.shear.any())
    throw Error(std::string("restore: the scene's cell ") + (scene.cell.shear.any() ? "is" : "is not") +
                " sheared (Cell/shear rate), the state's " + (s.cell.shear.any() ? "is" : "is not"));
  // The grains are placed by where the lists were last built (below): the balance too.
  const std::vector<Vec3> none;
  domain_->restore(s.domain, rank == 0 ? state_on_root.positions_at_build : none, s.step);
  // A deforming cell: the lists are built in the cell they were built in, with its images.
  if (deforming_) domain_->deform_cell(s.cell.at_build);
  if (s.cell.shear.any()) {
    ShearImages at_build = s.cell.shear;
    at_build.offset = s.cell.offset_at_build;
    domain_->shear_cell(at_build);
  }
  // Each grain to the rank whose block holds it where the lists were last built, in the order
  // of the ids; each history to the ranks of its grains (one for a wall's).
  const Decomposition& dec = domain_->decomposition();
  {
    const EngineState& all = state_on_root;  // rank 0's
    const std::vector<ParticleRecord> mine = hand_out<ParticleRecord>(
        grains.count, comm,
        [&](std::size_t k, std::vector<ParticleRecord>& out) {
          out.push_back(particle_record(all, grains.parts, k));
        },
        [&](const ParticleRecord& r) { return dec.owner_of(get(r.resume.x_built)); });
    s.particles.reserve(mine.size());
    for (const ParticleRecord& r : mine) append_record(s, grains.parts, r);
    // A history of a grain the state does not hold has no pair to go to (none is restored).
    auto owner = [&](GlobalId gid) {
      const auto it = std::lower_bound(all.particles.id.begin(), all.particles.id.end(), gid);
      if (it == all.particles.id.end() || *it != gid) return -1;
      return dec.owner_of(all.positions_at_build[static_cast<std::size_t>(it - all.particles.id.begin())]);
    };
    struct RoutedHistory {
      int to;
      ContactHistoryRecord record;
    };
    for (const RoutedHistory& h : hand_out<RoutedHistory>(
             grains.histories, comm,
             [&](std::size_t k, std::vector<RoutedHistory>&out) {
               const ContactHistoryRecord& c = all.history[k];
               const int to_a = owner(c.a), to_b = c.b >= 0 ? owner(c.b) : -1;
               if (to_a >= 0) out.push_back({to_a, c});
               if (to_b >= 0 && to_b != to_a) out.push_back({to_b, c});
             },
             [](const RoutedHistory&r) { return r.to; }))
      s.history.push_back(h.record);
  }
  // Spheres in a scene that pours ellipsoids (set_up): with their shapes, as in the run.
  if (shapes_) s.particles.ensure_shapes();

  // The particles of this rank's block, placed where the lists were last built: ownership, cell
  // order, ghosts and the lists themselves then follow from the positions the interrupted run
  // built them from (verlet_list.h), and the next rebuild comes at the same step.
  for (std::size_t k = 0; k < s.particles.size(); ++k) {
    append_state(p_, pack_state(s.particles, k));
    p_.x.back() = s.positions_at_build[k];
    if (shapes_) append_shape(p_, pack_shape(s.particles, k));
  }
  n_owned_ = static_cast<int>(p_.size());
  sort_by_cell(p_, range_);
  domain_->build_ghosts(p_, n_owned_);
  // The walls where the lists were last built, too.
  std::vector<PlaneWall> walls_at_build = walls_;
  for (std::size_t w = 0; w < walls_.size(); ++w) walls_at_build[w].point = wall_points_at_build_[w];
  lists_->build(p_, n_owned_, walls_at_build);
  history_.restore(lists_->pairs(), lists_->walls(), p_.id, s.history);
  if (deforming_) {
    domain_->deform_cell(s.domain.box);
    if (s.cell.shear.any()) domain_->shear_cell(s.cell.shear);
    cell_at_build_ = s.cell.at_build;
    offset_at_build_ = s.cell.offset_at_build;
    cell_l_ = s.cell.velocity_gradient;
    cell_flow_ = mean_flow(cell_l_, scene_.cell.shear);
    cell_stress_ = s.cell.stress;
    cell_stress_volume_ = s.cell.stress_volume;
    cell_stress_known_ = s.cell.stress_known;
    cell_work_ = s.cell.work;
  }
  // Back to the positions of the state, and the ghosts with them.
  for (int i = 0; i < n_owned_; ++i) p_.x[i] = s.particles.x[index_of(s.particles, p_.id[i])];
  if (domain_->has_ghosts()) domain_->refresh_ghosts(p_);

  // The last evaluation's per-particle output that the next step reads.
  const std::size_t n = p_.size();
  auto restore_field = [&](const std::vector<Vec3>& from, std::vector<Vec3>& to) {
    if (from.empty()) return;
    to.assign(n, Vec3::Zero());
    for (int i = 0; i < n_owned_; ++i) to[i] = from[index_of(s.particles, p_.id[i])];
  };
  restore_field(s.damping_force, out_.damping_force);
  restore_field(s.damping_torque, out_.damping_torque);
  restore_field(s.rolling_damping_torque, out_.rolling_damping_torque);
  if (!s.particle_elastic.empty()) {
    out_.particle_elastic.assign(n, ElasticEnergy{});
    dissipation_share_.assign(static_cast<std::size_t>(n_owned_), DissipatedEnergy{});
    for (int i = 0; i < n_owned_; ++i) {
      const std::size_t k = index_of(s.particles, p_.id[i]);
      out_.particle_elastic[i] = s.particle_elastic[k];
      dissipation_share_[i] = s.dissipation_share[k];
    }
  }
  out_.wall_force.assign(summation_ == Summation::deterministic ? lists_->walls().size() : walls_.size(),
                         Vec3::Zero());
  // The grains' poses of the last evaluation, so that the next one has their motion bounds.
  if (shapes_) posed_.update(p_);

  step_ = s.step;
  rebuilds_ = s.rebuilds;
  rebuild_pending_ = s.rebuild_pending;
  last_overlap_ratio_ = s.last_overlap_ratio;
  last_overlap_step_ = s.last_overlap_step;
  e0_ = s.initial_energy;
  removed_by_relaxation_ = s.removed_by_relaxation;
  if (s.wall_forces.size() != walls_.size() || s.wall_damping_forces.size() != walls_.size())
    throw Error("restore: the state's wall forces do not match its walls");
  restored_wall_loads_ = WallLoads{s.wall_forces, s.wall_damping_forces};
  // The global sums and counts are rank 0's to continue; the other ranks add from zero.
  if (is_root()) {
    out_.pair_contacts = s.pair_contacts;
    out_.wall_contacts = s.wall_contacts;
    for (int c = 0; c < kChannels; ++c) dissipated_[c] = ExactSum::from_state(s.dissipated[c]);
    solver_stats_ = s.solver_stats;
    reference_mass_ = s.reference_mass;
  }
  timings_ = {};
} catch (const std::bad_alloc&) {
  throw_out_of_memory(
      "the engine restored from the checkpoint (its state on every rank, the store, ghosts and lists)");
}

}  // namespace upgrain::dem
