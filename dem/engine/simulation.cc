#include "dem/engine/simulation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <utility>

#include "dem/boundary/container.h"
#include "dem/contact/contact_laws.h"
#include "dem/core/error.h"
#include "dem/core/out_of_memory.h"
#include "dem/engine/cell_stress.h"
#include "dem/engine/guards.h"
#include "dem/engine/particle_sums.h"
#include "dem/motion/grain_rotation.h"
#include "dem/parallel/exchange.h"
#include "dem/parallel/parallel_stress.h"

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

// The scene's particles on every rank, so that every rank derives the same box and radii:
// rank 0's store as flat records, with their shapes in `shapes` (same order) when it has
// them. Not called on one rank, where the store is the scene.
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

// What the scene's particles set for the engine: their count, the largest radius, and the
// heights of the lowest and highest centroid.
struct SceneExtent {
  long count = 0;
  double max_radius = 0.0;
  double z_min = 0.0, z_max = 0.0;

  void add(const Vec3& x, double radius) {
    z_min = count == 0 ? x[2] : std::min(z_min, x[2]);
    z_max = count == 0 ? x[2] : std::max(z_max, x[2]);
    max_radius = std::max(max_radius, radius);
    ++count;
  }
};

// The container footprint, from the floor (or the lowest particle surface) to the highest
// particle surface, with every grain as large as the largest (r_max); with a pour, up to the top
// of its inlet too, where the grains come from (docs/insertion.md).
Box default_box(const SceneConfig& scene, const SceneExtent& e, double r_max) {
  Box b;
  b.lo = Vec3(0.0, 0.0, e.count > 0 ? std::min(0.0, e.z_min - r_max) : 0.0);
  b.hi = Vec3(scene.container.lx, scene.container.ly, e.count > 0 ? std::max(0.0, e.z_max + r_max) : 0.0);
  if (scene.insertion.enabled()) b.hi.z() = std::max(b.hi.z(), scene.insertion.inlet_hi.z());
  // A periodic z is the cell [0, height] (docs/periodic.md).
  if (scene.container.periodic[2]) {
    b.lo.z() = 0.0;
    b.hi.z() = scene.container.height;
  }
  return b;
}

}  // namespace

Simulation::Simulation(const SceneConfig& scene, ParticleStore particles, MPI_Comm comm,
                       const EngineOptions& options)
    : Simulation(scene, std::move(particles), make_open_box(scene.container), comm, options) {}

// A std::bad_alloc anywhere in the construction (the broadcast scene, each rank's store, the
// ghosts and lists) is named (dem/core/out_of_memory.h).
Simulation::Simulation(const SceneConfig& scene, ParticleStore particles, std::vector<PlaneWall> walls,
                       MPI_Comm comm, const EngineOptions& options) try
    : scene_(scene),
      walls_(std::move(walls)),
      summation_(options.summation),
      g_(scene.effects.gravity ? Vec3(0, 0, -scene.gravity) : Vec3::Zero()),
      dt_(scene.time_step),
      material_{scene.friction, scene.damping_ratio},
      law_constants_(
          find_contact_law(scene.contact_law).constants(scene.particles.material, scene.law_parameters)),
      rolling_(rolling_parameters(scene.rolling_friction, scene.rolling_damping_ratio,
                                  scene.effects.twisting_resistance, scene.particles.material.youngs_modulus,
                                  scene.particles.material.poisson_ratio)) {
  if (scene.effects.rolling_resistance && !scene.effects.rotation)
    throw Error(
        "rolling resistance needs rotation: set Effects/rotation = true or Effects/rolling resistance = "
        "false");
  if (scene.effects.twisting_resistance && !scene.effects.rolling_resistance)
    throw Error(
        "twisting resistance needs rolling resistance: set Effects/rolling resistance = true or "
        "Effects/twisting "
        "resistance = false");
  if (!scene.effects.wall_friction) {
    for (auto& w : walls_) w.friction = 0.0;
  }
  for (const PlaneWall& w : walls_)
    if (!w.velocity.allFinite()) throw Error("the velocity of wall '" + w.name + "' is not finite");
  note_wall_motion();
  // Every rank holds the whole scene for a moment: rank 0's store on one rank, flat records
  // of it on more (each then keeps the particles of its block).
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<ShapeRecord> shapes_in;
  std::vector<StateRecord> all;
  if (size == 1)
    p_ = std::move(particles);
  else
    all = broadcast_particles(particles, comm, shapes_in);
  particles = ParticleStore{};
  SceneExtent extent;
  if (size == 1)
    for (std::size_t i = 0; i < p_.size(); ++i) extent.add(p_.x[i], p_.radius[i]);
  else
    for (const StateRecord& r : all) extent.add(get(r.x), r.radius);
  const bool shapes = size == 1 ? p_.has_shapes() : !shapes_in.empty();
  const double r_max = std::max(extent.max_radius, 1e-12);
  set_up(extent.count, extent.max_radius, shapes,
         options.box ? *options.box : default_box(scene, extent, r_max), comm, options);
  // A pour of ellipsoids into spheres: the spheres get their shapes (a = b = c).
  if (shapes_ && !shapes) {
    if (size == 1)
      p_.ensure_shapes();
    else
      for (const StateRecord& r : all) shapes_in.push_back(sphere_shape(r));
  }
  const Decomposition& dec = domain_->decomposition();
  // Into a periodic cell first (a packing's grains may lie a cell or more away, with their image
  // counters): each to the rank of its block.
  if (dec.cell().any()) {
    for (std::size_t i = 0; i < p_.size(); ++i) wrap(dec.cell(), p_.x[i], p_.image[i]);
    for (StateRecord& r : all) {
      Vec3 x = get(r.x);
      ImageCount n{r.image[0], r.image[1], r.image[2]};
      wrap(dec.cell(), x, n);
      put(r.x, x);
      for (int d = 0; d < 3; ++d) r.image[d] = n[d];
    }
  }
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (dec.owner_of(get(all[k].x)) != dec.rank()) continue;
    append_state(p_, all[k]);
    if (shapes_) append_shape(p_, shapes_in[k]);
  }
  all = {};
  shapes_in = {};
  n_owned_ = static_cast<int>(p_.size());
  rebuild();
  if (deforming_) record_next_ = true;
  evaluate_forces();
  if (deforming_) follow_cell_stress();
  // The force loop books a moving wall's work for the step that brought it to the evaluation
  // and for the next one, half each; there was no step before the first.
  if (walls_move_ && scene_.effects.energy_tracking) {
    const double in_half = wall_work_ahead(wall_loads()).work;
    if (is_root()) dissipated_[kWallWork].add(-in_half);
  }
  e0_ = energy();
  timings_ = {};  // step() only
} catch (const std::bad_alloc&) {
  throw_out_of_memory("the engine's particle store, ghosts and neighbour lists");
}

void Simulation::set_up(long count, double max_radius, bool shapes, const Box& box, MPI_Comm comm,
                        const EngineOptions& options) {
  options_ = options;
  // A pour brings grains as large as the scene's largest, and its shapes (docs/insertion.md):
  // the range, the skin and the force loop are chosen for them from the start, so that a run
  // and its restart choose the same.
  if (scene_.insertion.enabled()) {
    max_radius = std::max(max_radius, scene_.particles.largest_radius());
    shapes = shapes || has_shapes(scene_.particles.shapes);
  }
  shapes_ = shapes;
  rotation_ = scene_.effects.integrates_rotation(shapes_);
  loops_ = select_force_loops(scene_.effects, shapes_, summation_, scene_.contact_law);
  history_ = ContactHistory(
      {scene_.effects.friction, scene_.effects.wall_friction, scene_.effects.rolling_resistance, shapes_});
  n_global_ = count;
  max_radius_ = max_radius;
  // The skin in units of the largest diameter.
  skin_ = scene_.neighbor_skin * 2.0 * max_radius_;
  max_radius_ = std::max(max_radius_, 1e-12);
  range_ = 2.0 * max_radius_ + skin_;
  // The scene's periodic axes, and any the options add (a test's own box).
  for (int d = 0; d < 3; ++d) options_.periodic[d] = options.periodic[d] || scene_.container.periodic[d];
  // A deforming cell (docs/periodic.md, "A cell that deforms"): along periodic axes, no pour and
  // no gravity along a deforming axis; its grid sized for its growth. The blocks' planes follow
  // the cell in fractional coordinates between the load balance's moves.
  deforming_ = scene_.cell.any();
  if (deforming_) {
    for (int d = 0; d < 3; ++d) {
      if (scene_.cell.axis[d].mode == CellAxisMode::fixed) continue;
      const std::string axis(1, "xyz"[d]);
      if (!options_.periodic[d])
        throw Error("a deforming cell: the axis " + axis +
                    " deforms but is not periodic (Container/periodic axes)");
      if (g_[d] != 0.0)
        throw Error("a deforming cell: gravity has a component along the deforming axis " + axis);
    }
    if (scene_.insertion.enabled())
      throw Error("a deforming cell: insertion during the run is not available");
    // A sheared cell (Lees-Edwards images, docs/periodic.md, "Shear"): its shear axis in one block.
    if (const CellShearControl& c = scene_.cell.shear; c.any()) {
      for (int d : c.component) {
        if (!options_.periodic[d])
          throw Error(std::string("a sheared cell: the axis ") + "xyz"[d] +
                      " is not periodic (Container/periodic axes)");
        if (g_[d] != 0.0)
          throw Error(std::string("a sheared cell: gravity has a component along its axis ") + "xyz"[d]);
      }
      if (c.shear() == c.gradient()) throw Error("a sheared cell: its shear and gradient axes are the same");
      options_.unsplit_axis = c.shear();
    }
    options_.cell_growth = scene_.cell.max_growth;
    cell_l_ = initial_velocity_gradient(scene_.cell);
    cell_start_ = box;
    cell_flow_ = mean_flow(cell_l_, scene_.cell.shear);
  }
  domain_ = std::make_unique<Domain>(comm, box, range_, shapes_, options_);
  if (deforming_) {
    domain_->deform_cell(domain_->decomposition().cell().box);
    cell_at_build_ = domain_->decomposition().cell().box;
    if (scene_.cell.shear.any())
      domain_->shear_cell(ShearImages{scene_.cell.shear.shear(), scene_.cell.shear.gradient(), 0.0, 0});
  }
  lists_ = std::make_unique<VerletList>(
      max_radius_, skin_, summation_ == Summation::deterministic ? PairOrder::global_id : PairOrder::local);
}

void Simulation::step() {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  const int n = n_owned_;
  const double half = 0.5 * dt_;
  // Velocity Verlet, first half kick and drift (Allen and Tildesley 2017, eq. 3.19), with the
  // Verlet list's displacement check in the same pass, then the rotational half.
  const std::vector<Vec3>& x_built = lists_->positions_at_build();
  double limit2 = lists_->rebuild_displacement2();
  bool moved = false;
  const PeriodicCell& cell = domain_->decomposition().cell();
  const bool periodic = cell.any();
  // A deforming cell: its faces move with the mean flow this step, and a pair across a face
  // comes closer by up to the change of the cell's lengths since the lists were built, which
  // the grains' own displacements must leave room for (verlet_list.h: two grains of a pair may
  // move half a skin each).
  // A sheared cell's images slide by the change of its offset besides.
  const MeanFlow flow = cell_flow_;
  const FlowDecay decay = deforming_ ? flow_decay(flow, half) : FlowDecay{};
  Box next_cell;
  double next_offset = 0.0;
  if (deforming_) {
    next_cell = advanced_cell_box(cell, cell_l_, dt_);
    Vec3 moved_faces = (next_cell.hi - next_cell.lo) - (cell_at_build_.hi - cell_at_build_.lo);
    if (cell.shear.any()) {
      next_offset = advanced_offset(cell, cell_l_, dt_);
      moved_faces[cell.shear.shear] += std::abs(next_offset - offset_at_build_);
    }
    const double change = moved_faces.norm();
    const double room = std::sqrt(limit2) - 0.5 * change;
    moved = !(room > 0.0);
    limit2 = room > 0.0 ? room * room : 0.0;
  }
  for (int i = 0; i < n; ++i) {
    if (deforming_) {
      // SLLOD (cell_motion.h): the stored peculiar velocity u takes F/m - L u, its -L u
      // exactly over the half step (u e^(-L dt/2)) before this half kick and after the second,
      // a symmetric splitting; the drift is by the absolute velocity u + L x.
      p_.v[i] = decay(p_.v[i]) + half * (p_.force[i] * p_.inv_mass[i] + g_);
      p_.x[i] += dt_ * (p_.v[i] + flow.of(p_.x[i]));
      snap(cell, p_.x[i]);
    } else {
      p_.v[i] += half * (p_.force[i] * p_.inv_mass[i] + g_);
      p_.x[i] += dt_ * p_.v[i];
      // Along a periodic axis, onto the cell's grid: its images are then exact (periodic_cell.h).
      if (periodic) snap(cell, p_.x[i]);
    }
    // Written so that a non-finite position counts as moved: the rebuild's guard then names
    // the particle at once (a NaN compares false, and would otherwise never rebuild).
    moved = moved || !((p_.x[i] - x_built[i]).squaredNorm() <= limit2);
  }
  if (rotation_) rotation_first_half(p_, static_cast<std::size_t>(n), half, dt_);
  if (deforming_) {
    domain_->deform_cell(next_cell);
    if (cell.shear.any()) {
      ShearImages le = cell.shear;
      le.offset = next_offset;
      domain_->shear_cell(le);
    }
  }
  // Grains inserted before this step: the same half kick and drift (their force is zero: they
  // touch nothing), joined to the others by this step's rebuild (insert()).
  for (std::size_t i = 0; i < arrivals_.size(); ++i) {
    arrivals_.v[i] += half * g_;
    arrivals_.x[i] += dt_ * arrivals_.v[i];
  }
  if (rotation_) rotation_first_half(arrivals_, arrivals_.size(), half, dt_);
  // Moving walls drift with the grains; a wall that has moved half a skin since the lists were
  // built rebuilds them, as a grain does (its entries reach a skin: verlet_list.h). The walls
  // are the same on every rank, so is this decision.
  if (walls_move_)
    for (std::size_t w = 0; w < walls_.size(); ++w) {
      walls_[w].point += dt_ * walls_[w].velocity;
      moved = moved || (walls_[w].point - wall_points_at_build_[w]).squaredNorm() > limit2;
    }
  // Second half of the work of the previous step's damping forces, with v(k+1/2); the owned
  // particles are still those of that evaluation. Damping acts along the normal through the
  // centroids of spheres: no torque; ellipsoids' normal misses the centroid.
  // Deterministic summation: each grain's work is its own share, as its share of the evaluation.
  const bool per_grain = dissipation_per_grain();
  if (!out_.damping_force.empty()) {
    const bool torques = !out_.damping_torque.empty();
    double work = 0.0;
    for (int i = 0; i < n; ++i) {
      double w = out_.damping_force[i].dot(p_.v[i]);
      if (torques) w += out_.damping_torque[i].dot(p_.omega[i]);
      if (per_grain)
        dissipation_share_[i].damping -= half * w;
      else
        work += w;
    }
    if (!per_grain) dissipated_[kDamping].add(-half * work);
  }
  // The same for the rolling dashpot (dem/contact/rolling_resistance.h).
  if (!out_.rolling_damping_torque.empty()) {
    double work = 0.0;
    for (int i = 0; i < n; ++i) {
      const double w = out_.rolling_damping_torque[i].dot(p_.omega[i]);
      if (per_grain)
        dissipation_share_[i].rolling -= half * w;
      else
        work += w;
    }
    if (!per_grain) dissipated_[kRolling].add(-half * work);
  }
  // One reduction per step carries both global decisions: rebuild now (every rank at the
  // same steps), and the runaway-overlap guard of the previous evaluation.
  double local[2] = {moved || rebuild_pending_ ? 1.0 : 0.0, last_overlap_ratio_};
  double global[2] = {0.0, 0.0};
  const Clock::time_point t1 = Clock::now();
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, comm());
  const Clock::time_point t2 = Clock::now();
  check_overlap(global[1]);  // every rank has the same maximum
  const bool rebuilding = global[0] > 0.0;
  if (rebuilding) {
    rebuild();
    rebuild_pending_ = false;
  } else if (domain_->has_ghosts())
    domain_->refresh_ghosts(p_);
  const Clock::time_point t3 = Clock::now();
  // The cell's stress needs this evaluation's contacts.
  if (deforming_) record_next_ = true;
  evaluate_forces();
  const Clock::time_point t4 = Clock::now();
  // Fast summation: the ghosts' shares go home (LAMMPS's reverse communication).
  if (summation_ == Summation::fast && domain_->has_ghosts()) {
    // A fixed array: no allocation per step.
    std::array<std::vector<Vec3>*, 5> sums{&p_.force};
    std::size_t m = 1;
    if (rotation_) sums[m++] = &p_.torque;
    for (std::vector<Vec3>* v : {&out_.damping_force, &out_.damping_torque, &out_.rolling_damping_torque})
      if (!v->empty()) sums[m++] = v;
    domain_->return_ghost_sums(std::span<std::vector<Vec3>* const>(sums.data(), m));
  }
  const Clock::time_point t5 = Clock::now();
  // Second half kick with the new forces.
  if (deforming_)
    for (int i = 0; i < n_owned_; ++i) p_.v[i] = decay(p_.v[i] + half * (p_.force[i] * p_.inv_mass[i] + g_));
  else
    for (int i = 0; i < n_owned_; ++i) p_.v[i] += half * (p_.force[i] * p_.inv_mass[i] + g_);
  if (rotation_) rotation_second_half(p_, static_cast<std::size_t>(n_owned_), half);
  if (deforming_) follow_cell_stress();
  ++step_;
  last_overlap_step_ = step_;  // the evaluation was of this step's positions, at time()
  const Clock::time_point t6 = Clock::now();
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  timings_.integrate += seconds(t0, t1) + seconds(t5, t6);
  timings_.reduction += seconds(t1, t2);
  (rebuilding ? timings_.rebuild : timings_.ghost_refresh) += seconds(t2, t3);
  timings_.ghost_refresh += seconds(t4, t5);
  timings_.forces += seconds(t3, t4);
  ++timings_.steps;
}

void Simulation::run(long steps) {
  for (long s = 0; s < steps; ++s) step();
}

void Simulation::rebuild() try {
  const double messages_before = domain_->message_seconds();
  std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  check_finite();
  timings_.rebuild_messages += seconds_since(t);
  if (dissipation_per_grain()) settle_dissipation();
  // A sheared cell's tilt remapped to its least tilted basis, now that the ghosts are rebuilt:
  // the lattice of images is the same, no grain moves (periodic_cell.h).
  if (const PeriodicCell& c = domain_->decomposition().cell(); c.shear.any())
    domain_->shear_cell(remapped(c.shear, c.length(c.shear.shear)));
  // Histories of the contacts, keyed by global ids, before local indices change. The
  // separation budgets of ellipsoid pairs rest on grains keeping their local index, which
  // depends on the decomposition: the deterministic summation drops them.
  std::vector<ContactHistoryRecord> records;
  history_.collect(lists_->pairs(), lists_->walls(), p_.id, summation_ == Summation::fast, records);
  // Drop the ghosts; they are rebuilt below from the new owners.
  truncate_store(p_, static_cast<std::size_t>(n_owned_));
  // Inserted grains join the owned ones here, before the migration (insert()).
  for (std::size_t i = 0; i < arrivals_.size(); ++i) {
    append_state(p_, pack_state(arrivals_, i));
    if (shapes_) append_shape(p_, pack_shape(arrivals_, i));
  }
  arrivals_ = ParticleStore{};
  arrivals_pending_ = false;
  domain_->migrate(p_, records, lists_->slots_per_owned(), step_, time());
  n_owned_ = static_cast<int>(p_.size());
  long count = n_owned_;
  long total = 0;
  t = std::chrono::steady_clock::now();
  MPI_Allreduce(&count, &total, 1, MPI_LONG, MPI_SUM, comm());
  timings_.rebuild_messages += seconds_since(t);
  const std::string lost = lost_particles(total, n_global_, step_);
  if (!lost.empty()) throw CollectiveError(lost);
  sort_unique(records);
  // Memory locality only: the lists fix the order of every sum.
  sort_by_cell(p_, range_);
  domain_->build_ghosts(p_, n_owned_);
  lists_->build(p_, n_owned_, walls_);
  wall_points_at_build_.clear();
  for (const PlaneWall& w : walls_) wall_points_at_build_.push_back(w.point);
  cell_at_build_ = domain_->decomposition().cell().box;
  offset_at_build_ = domain_->decomposition().cell().shear.offset;
  history_.restore(lists_->pairs(), lists_->walls(), p_.id, records);
  if (dissipation_per_grain())
    dissipation_share_.assign(static_cast<std::size_t>(n_owned_), DissipatedEnergy{});
  ++rebuilds_;
  domain_->measure_balance(n_owned_, lists_->slots_per_owned());
  timings_.rebuild_messages += domain_->message_seconds() - messages_before;
} catch (const std::bad_alloc&) {
  throw_out_of_memory("the neighbour lists and ghosts at a rebuild");
}

void Simulation::evaluate_forces() {
  ForceInput in;
  in.particles = &p_;
  in.n_owned = n_owned_;
  in.pairs = &lists_->pairs();
  in.wall_entries = &lists_->walls();
  in.walls = &walls_;
  in.history = &history_;
  in.dissipation = dissipation_share_.data();
  in.material = material_;
  in.law = &law_constants_;
  in.rolling = rolling_;
  in.dt = dt_;
  if (deforming_) in.mean_flow = &cell_flow_;
  in.posed = &posed_;
  in.solver_settings = scene_.contact_solver;
  in.solver_stats = &solver_stats_;
  in.out = &out_;
  recorded_ = record_next_;
  restored_wall_loads_.reset();
  (record_next_ ? loops_.recording : loops_.plain)(in);
  if (!record_next_) out_.contacts.clear();
  record_next_ = false;
  if (!dissipation_per_grain()) {
    DissipatedEnergy step;
    book_with_wall_work(out_.energy, step);
    add_to(dissipated_, step);
  }
  last_overlap_ratio_ = out_.max_overlap_ratio;
  last_overlap_particle_ = out_.max_overlap_particle;
  last_overlap_partner_ = out_.max_overlap_partner;
  last_overlap_step_ = step_;
}

void Simulation::check_overlap(double global_max) const {
  if (!(global_max > kRunawayOverlapRatio)) return;
  // The rank whose own maximum it is names the contact (the lowest such rank).
  struct {
    double ratio;
    int rank;
  } mine{last_overlap_ratio_, rank()}, holder{};
  MPI_Allreduce(&mine, &holder, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm());
  GlobalId ids[2] = {last_overlap_particle_, last_overlap_partner_};
  MPI_Bcast(ids, 2, MPI_INT64_T, holder.rank, comm());
  OverlapSite site{ids[0], ids[1], {}};
  if (site.partner < 0 && -site.partner - 1 < static_cast<GlobalId>(walls_.size()))
    site.wall = walls_[static_cast<std::size_t>(-site.partner - 1)].name;
  throw CollectiveError(runaway_overlap(global_max, kRunawayOverlapRatio, last_overlap_step_,
                                        static_cast<double>(last_overlap_step_) * dt_, scene_, site,
                                        assembly_load()));
}

AssemblyLoad Simulation::assembly_load() const {
  // Known where the engine follows the cell's Love-Weber stress: a deforming periodic cell (the
  // same on every rank).
  if (!(deforming_ && cell_stress_known_)) return {};
  double sums[2] = {static_cast<double>(out_.pair_contacts), 0.0};
  for (int i = 0; i < n_owned_; ++i) sums[1] += p_.volume(static_cast<std::size_t>(i));
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, comm());
  const Box& box = decomposition().cell().box;
  return {.pressure = -cell_stress_.trace() / 3.0,
          .coordination = 2.0 * sums[0] / static_cast<double>(std::max(particle_count(), 1L)),
          .solid_fraction = sums[1] / (box.hi - box.lo).prod()};
}

void Simulation::add_to(std::array<ExactSum, kChannels>& sums, const DissipatedEnergy& d) {
  sums[kDamping].add(d.damping);
  sums[kFriction].add(d.friction);
  sums[kStiffnessChange].add(d.stiffness_change);
  sums[kRolling].add(d.rolling);
  sums[kRollingStiffnessChange].add(d.rolling_stiffness_change);
  sums[kWallWork].add(d.wall_work);
}

void Simulation::settle_dissipation() {
  for (const DissipatedEnergy& share : dissipation_share_) add_to(dissipated_, share);
  dissipation_share_.assign(static_cast<std::size_t>(n_owned_), DissipatedEnergy{});
}

void Simulation::remove_wall(const std::string& name) {
  for (PlaneWall& w : walls_) {
    if (w.name != name) continue;
    // Far along its own normal's opposite side (kRemovedWallDistance).
    set_wall_velocity(static_cast<std::size_t>(&w - walls_.data()), Vec3::Zero());
    w.point -= kRemovedWallDistance * w.normal;
    // Its wall entries go at the next step's rebuild: rebuilding now would reorder the
    // particles under the last evaluation's per-particle output, whose damping work the next
    // step still books.
    rebuild_pending_ = true;
    return;
  }
  throw Error("no wall named '" + name + "' to remove");
}

void Simulation::add_wall(const PlaneWall& wall) {
  for (const PlaneWall& w : walls_)
    if (w.name == wall.name) throw Error("a wall named '" + wall.name + "' is already in the scene");
  walls_.push_back(wall);
  if (!scene_.effects.wall_friction) walls_.back().friction = 0.0;
  // Until the next evaluation the new wall carries no load. The loads kept per wall (a
  // restored state's, and the fast summation's per-wall sums) get its zero entry, so that
  // wall_loads() has one entry per wall on every rank (a servo reads it before the first step).
  if (restored_wall_loads_) {
    restored_wall_loads_->force.push_back(Vec3::Zero());
    restored_wall_loads_->damping.push_back(Vec3::Zero());
  }
  if (summation_ == Summation::fast) {
    out_.wall_force.resize(walls_.size(), Vec3::Zero());
    if (!out_.wall_damping.empty()) out_.wall_damping.resize(walls_.size(), Vec3::Zero());
  }
  // Its point at build: far enough that the next step rebuilds (the entries come with it).
  wall_points_at_build_.push_back(wall.point);
  note_wall_motion();
  rebuild_pending_ = true;
}

std::size_t Simulation::wall_index(const std::string& name) const {
  for (std::size_t w = 0; w < walls_.size(); ++w)
    if (walls_[w].name == name) return w;
  throw Error("no wall named '" + name + "'");
}

void Simulation::set_wall_velocity(std::size_t wall, const Vec3& velocity) {
  if (wall >= walls_.size()) throw Error("no wall " + std::to_string(wall) + " to move");
  if (!velocity.allFinite()) throw Error("the velocity of wall '" + walls_[wall].name + "' is not finite");
  if (velocity == walls_[wall].velocity) return;
  // The last evaluation booked its wall's work for the coming step with the old velocity
  // (force_loop_body.h): the half that belongs to the coming step is the new velocity's.
  if (scene_.effects.energy_tracking) {
    const WallLoads loads = wall_loads();
    const Vec3 change = velocity - walls_[wall].velocity;
    if (is_root()) {
      dissipated_[kWallWork].add(-0.5 * dt_ * loads.force[wall].dot(change));
      dissipated_[kDamping].add(-0.5 * dt_ * loads.damping[wall].dot(change));
    }
  }
  walls_[wall].velocity = velocity;
  note_wall_motion();
}

void Simulation::note_wall_motion() {
  walls_move_ = std::any_of(walls_.begin(), walls_.end(),
                            [](const PlaneWall& w) { return w.velocity != Vec3::Zero(); });
}

void Simulation::set_gravity(const Vec3& g) {
  g_ = g;
  e0_ = energy();
}

void Simulation::check_finite() const { throw_if_any(comm(), non_finite_state(p_, n_owned_, step_, time())); }

void Simulation::on_root(const std::function<void()>& work) const { run_on_root(comm(), work); }

const ParticleStore& Simulation::whole_state() {
  gathered_ = gather_sorted_by_id();
  std::string error;
  if (is_root()) {
    double mass = 0.0;
    for (std::size_t i = 0; i < gathered_.size(); ++i) mass += gathered_.mass(i);
    if (reference_mass_ < 0.0) reference_mass_ = mass;
    error = inconsistent_state(gathered_, n_global_, mass, reference_mass_, step_);
  }
  throw_if_any(comm(), error);
  return gathered_;
}

namespace {

struct ShapedStateRecord {
  StateRecord state;
  ShapeRecord shape;
};

GlobalId record_id(const StateRecord& r) { return r.gid; }
GlobalId record_id(const ShapedStateRecord& r) { return r.state.gid; }

// The records `collect` brings to this rank from the owned particles of every rank, sorted by
// global id: `pack` makes a record of one particle, `append` adds one to the result.
template <typename Record, typename Pack, typename Append, typename Collect>
ParticleStore collected_by_id(int n_owned, Pack pack, Append append, Collect collect) {
  std::vector<Record> mine;
  mine.reserve(static_cast<std::size_t>(n_owned));
  for (int i = 0; i < n_owned; ++i) mine.push_back(pack(static_cast<std::size_t>(i)));
  std::vector<Record> all = collect(mine);
  std::vector<Record>().swap(mine);
  std::sort(all.begin(), all.end(),
            [&](const Record& a, const Record& b) { return record_id(a) < record_id(b); });
  ParticleStore out;
  out.reserve(all.size());
  for (const Record& r : all) append(out, r);
  return out;
}

// The grains of `wanted` appended to `s.grains` from the ranks whose rows hold them: each
// asks the holder of each id, which answers with its record (`pack` of one of its rows).
template <typename Record, typename Pack, typename Append>
void add_from_rows(IdSlice& s, const std::vector<GlobalId>& wanted, MPI_Comm comm, Pack pack, Append append) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  struct Request {
    GlobalId gid;
    int from;
  };
  struct Reply {
    int to;
    Record record;
  };
  std::vector<Request> ask;
  ask.reserve(wanted.size());
  for (const GlobalId gid : wanted) ask.push_back({gid, rank});
  const std::vector<Request> asked =
      send_to_ranks(ask, comm, [&](const Request& q) { return row_owner(q.gid, s.total_rows, size); });
  std::vector<Reply> replies;
  replies.reserve(asked.size());
  std::string error;
  for (const Request& q : asked) {
    const long row = q.gid - s.first_row;
    if (row < 0 || row >= static_cast<long>(s.rows) || s.grains.id[static_cast<std::size_t>(row)] != q.gid) {
      error =
          "output: grain " + std::to_string(q.gid) + " is not in the rows of rank " + std::to_string(rank);
      break;
    }
    replies.push_back({q.from, pack(s.grains, static_cast<std::size_t>(row))});
  }
  throw_if_any(comm, error);
  std::vector<Reply> got = send_to_ranks(replies, comm, [](const Reply& r) { return r.to; });
  std::sort(got.begin(), got.end(),
            [](const Reply& a, const Reply& b) { return record_id(a.record) < record_id(b.record); });
  s.grains.reserve(s.rows + got.size());
  for (const Reply& r : got) append(s.grains, r.record);
}

}  // namespace

template <class Collect>
ParticleStore Simulation::collect_by_id(Collect collect) const {
  if (shapes_)
    return collected_by_id<ShapedStateRecord>(
        n_owned_,
        [&](std::size_t i) {
          return ShapedStateRecord{pack_state(p_, i), pack_shape(p_, i)};
        },
        [](ParticleStore& out, const ShapedStateRecord& r) {
          append_state(out, r.state);
          append_shape(out, r.shape);
        },
        collect);
  return collected_by_id<StateRecord>(
      n_owned_, [&](std::size_t i) { return pack_state(p_, i); },
      [](ParticleStore& out, const StateRecord& r) { append_state(out, r); }, collect);
}

ParticleStore Simulation::gather_sorted_by_id() const {
  return collect_by_id([&](const auto& mine) { return gather_to_root(mine, comm()); });
}

IdSlice Simulation::whole_state_slice() {
  int size = 1;
  MPI_Comm_size(comm(), &size);
  IdSlice s;
  s.total_rows = n_global_;
  s.shapes = shapes_;
  s.first_row = first_row(n_global_, rank(), size);
  const long end = first_row(n_global_, rank() + 1, size);
  s.grains = collect_by_id([&](const auto& mine) {
    return send_to_ranks(mine, comm(),
                         [&](const auto& r) { return row_owner(record_id(r), n_global_, size); });
  });
  s.rows = s.grains.size();
  // Every grain once: this rank's rows hold exactly the ids first_row .. end - 1.
  long misplaced = static_cast<long>(s.grains.size()) == end - s.first_row ? 0 : 1;
  for (std::size_t k = 0; k < s.grains.size() && misplaced == 0; ++k)
    if (s.grains.id[k] != s.first_row + static_cast<long>(k)) misplaced = 1;
  // The mass in id order, continued from rank to rank: the sum whole_state() takes, bit for bit
  // (a chain of size - 1 messages of one double, at output time only).
  double mass = 0.0;
  if (rank() > 0) MPI_Recv(&mass, 1, MPI_DOUBLE, rank() - 1, 0, comm(), MPI_STATUS_IGNORE);
  for (std::size_t k = 0; k < s.grains.size(); ++k) mass += s.grains.mass(k);
  if (rank() + 1 < size) MPI_Send(&mass, 1, MPI_DOUBLE, rank() + 1, 0, comm());
  if (size > 1 && rank() == size - 1) MPI_Send(&mass, 1, MPI_DOUBLE, 0, 1, comm());
  if (size > 1 && is_root()) MPI_Recv(&mass, 1, MPI_DOUBLE, size - 1, 1, comm(), MPI_STATUS_IGNORE);
  long counts[2] = {static_cast<long>(s.grains.size()), misplaced};
  MPI_Reduce(is_root() ? MPI_IN_PLACE : counts, counts, 2, MPI_LONG, MPI_SUM, 0, comm());
  std::string error;
  if (is_root()) {
    if (reference_mass_ < 0.0) reference_mass_ = mass;
    error = inconsistent_state(counts[0], counts[1] == 0, n_global_, mass, reference_mass_, step_);
  }
  throw_if_any(comm(), error);
  return s;
}

void Simulation::add_other_rows(IdSlice& slice, const std::vector<GlobalId>& wanted) const {
  if (shapes_)
    add_from_rows<ShapedStateRecord>(
        slice, wanted, comm(),
        [](const ParticleStore& p, std::size_t i) {
          return ShapedStateRecord{pack_state(p, i), pack_shape(p, i)};
        },
        [](ParticleStore& out, const ShapedStateRecord& r) {
          append_state(out, r.state);
          append_shape(out, r.shape);
        });
  else
    add_from_rows<StateRecord>(
        slice, wanted, comm(), [](const ParticleStore& p, std::size_t i) { return pack_state(p, i); },
        [](ParticleStore& out, const StateRecord& r) { append_state(out, r); });
}

std::vector<int> Simulation::gather_owners_sorted_by_id() const {
  struct Owned {
    GlobalId gid;
    int rank;
  };
  std::vector<Owned> mine(static_cast<std::size_t>(n_owned_));
  for (int i = 0; i < n_owned_; ++i) mine[static_cast<std::size_t>(i)] = {p_.id[i], rank()};
  std::vector<Owned> all = gather_to_root(mine, comm());
  std::sort(all.begin(), all.end(), [](const Owned& a, const Owned& b) { return a.gid < b.gid; });
  std::vector<int> owner(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) owner[k] = all[k].rank;
  return owner;
}

std::vector<Box> Simulation::compute_grid_blocks() const { return dem::compute_grid_blocks(decomposition()); }

int Simulation::owner_of_local(std::size_t i) const {
  return i < static_cast<std::size_t>(n_owned_) ? rank() : domain_->ghost_owner(i);
}

GridStress Simulation::grid_stress(const RegularGrid& grid) const {
  if (!recorded_) throw Error("grid stress: no contacts recorded at the last step (request_contacts())");
  if (summation_ == Summation::deterministic)
    return parallel_grid_stress(p_, n_owned_, out_.contacts, grid, grain_dynamics(), comm(),
                                decomposition().cell());
  return summed_grid_stress(p_, n_owned_, out_.contacts, grid, grain_dynamics(), comm(),
                            decomposition().cell());
}

ComputeGridStress Simulation::compute_grid_stress() const {
  if (!recorded_) throw Error("grid stress: no contacts recorded at the last step (request_contacts())");
  if (summation_ == Summation::deterministic)
    return parallel_compute_grid_stress(p_, n_owned_, out_.contacts, decomposition(), grain_dynamics());
  std::vector<int> owner(p_.size());
  for (std::size_t i = 0; i < owner.size(); ++i) owner[i] = owner_of_local(i);
  return summed_compute_grid_stress(p_, n_owned_, out_.contacts, decomposition(), owner, grain_dynamics());
}

std::vector<ContactRecord> Simulation::gather_contacts_by_id(bool walls_only) const {
  std::vector<ContactRecord> all = gather_to_root(contact_records(walls_only), comm());
  std::sort(all.begin(), all.end());
  return all;
}

std::vector<ContactRecord> Simulation::contacts_by_id_slice() const {
  const int size = ranks();
  std::vector<ContactRecord> mine =
      send_to_ranks(contact_records(false), comm(),
                    [&](const ContactRecord& r) { return row_owner(r.a, n_global_, size); });
  std::sort(mine.begin(), mine.end());
  return mine;
}

std::vector<ContactRecord> Simulation::contacts_of_rows(IdSlice& slice) const {
  std::vector<ContactRecord> contacts = contacts_by_id_slice();
  const long end = slice.first_row + static_cast<long>(slice.rows);
  std::vector<GlobalId> partners;
  for (const ContactRecord& c : contacts)
    if (c.b >= 0 && (c.b < slice.first_row || c.b >= end)) partners.push_back(c.b);
  std::sort(partners.begin(), partners.end());
  partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
  add_other_rows(slice, partners);
  return contacts;
}

std::vector<ContactRecord> Simulation::contact_records(bool walls_only) const {
  if (!recorded_) throw Error("contacts: none recorded at the last step (request_contacts())");
  std::vector<ContactRecord> mine;
  for (const ContactSample& c : out_.contacts) {
    // Walls belong to owned particles. A pair is sent once: deterministic, by the owner of its
    // lower id (its first particle); fast, by the rank that evaluated it, turned to put the
    // lower id first.
    if (c.with_wall()) {
      ContactRecord r{p_.id[c.a], wall_key(c.wall()), {}, {}};
      put(r.point, c.point);
      put(r.force, c.force_on_a);
      mine.push_back(r);
      continue;
    }
    if (walls_only || (summation_ == Summation::deterministic && c.a >= n_owned_)) continue;
    const bool a_lower = p_.id[c.a] < p_.id[c.b];
    ContactRecord r{a_lower ? p_.id[c.a] : p_.id[c.b], a_lower ? p_.id[c.b] : p_.id[c.a], {}, {}};
    put(r.point, c.point);
    put(r.force, a_lower ? c.force_on_a : Vec3(-c.force_on_a));
    mine.push_back(r);
  }
  return mine;
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

EnergyBalance Simulation::energy() const {
  // Kinetic, potential and elastic energies, and this rank's cumulative dissipation.
  constexpr int kTerms =
      6;  // kinetic translational, rotational, potential, elastic normal, tangential, rolling
  const bool elastic_per_particle = !out_.particle_elastic.empty();
  auto terms = [&](int i, double* e) {
    const auto k = static_cast<std::size_t>(i);
    const double m = p_.mass(k);
    e[0] = 0.5 * m * p_.v[i].squaredNorm();  // a deforming cell's: peculiar (cell_motion.h)
    e[1] = rotation_ ? p_.rotational_energy(k) : 0.0;
    // The unwrapped position (periodic_cell.h): a grain that crosses a periodic face along
    // gravity (an incline) keeps a continuous potential energy.
    e[2] = -m * g_.dot(unwrapped(domain_->decomposition().cell(), p_.x[i], p_.image[i]));
    e[3] = elastic_per_particle ? out_.particle_elastic[k].normal : 0.0;
    e[4] = elastic_per_particle ? out_.particle_elastic[k].tangential : 0.0;
    e[5] = elastic_per_particle ? out_.particle_elastic[k].rolling : 0.0;
  };
  double sums[kTerms + kChannels] = {};
  // The dissipation: exact sums over the ranks (the same bits on every rank), with the grains'
  // shares since the last rebuild (added to a copy: asking changes nothing).
  std::array<ExactSum, kChannels> total = dissipated_;
  for (const DissipatedEnergy& share : dissipation_share_) add_to(total, share);
  for (int c = 0; c < kChannels; ++c) sums[kTerms + c] = total[c].reduced(comm()).value();
  if (summation_ == Summation::deterministic) {
    // Per particle in global-id order on rank 0 (bitwise rank-independent).
    struct Record {
      GlobalId gid;
      double e[kTerms];
    };
    std::vector<Record> mine(static_cast<std::size_t>(n_owned_));
    for (int i = 0; i < n_owned_; ++i) {
      mine[i].gid = p_.id[i];
      terms(i, mine[i].e);
    }
    std::vector<Record> all = gather_to_root(mine, comm());
    std::sort(all.begin(), all.end(), [](const Record& a, const Record& b) { return a.gid < b.gid; });
    for (const Record& r : all)
      for (int k = 0; k < kTerms; ++k) sums[k] += r.e[k];
    MPI_Bcast(sums, kTerms, MPI_DOUBLE, 0, comm());
  } else {
    // In local order, the elastic energies from the force loop, reduced over the ranks.
    double e[kTerms];
    for (int i = 0; i < n_owned_; ++i) {
      terms(i, e);
      sums[0] += e[0];
      if (rotation_) sums[1] += e[1];
      sums[2] += e[2];
    }
    sums[3] = out_.energy.elastic_normal;
    sums[4] = out_.energy.elastic_tangential;
    sums[5] = out_.energy.elastic_rolling;
    if (ranks() > 1) MPI_Allreduce(MPI_IN_PLACE, sums, kTerms, MPI_DOUBLE, MPI_SUM, comm());
  }
  EnergyBalance b;
  b.kinetic_translational = sums[0];
  b.kinetic_rotational = sums[1];
  b.potential = sums[2];
  b.elastic_normal = sums[3];
  b.elastic_tangential = sums[4];
  b.elastic_rolling = sums[5];
  b.dissipated_damping = sums[6];
  b.dissipated_friction = sums[7];
  b.tangential_stiffness_change = sums[8];
  b.dissipated_rolling = sums[9];
  b.rolling_stiffness_change = sums[10];
  b.work_by_walls = sums[11];
  if (walls_move_) {
    // Less what the last evaluation booked ahead for the coming step.
    const WallWorkAhead ahead = wall_work_ahead(wall_loads());
    b.work_by_walls -= ahead.work;
    b.dissipated_damping -= ahead.damping;
  }
  b.removed_by_relaxation = removed_by_relaxation_;
  b.work_by_cell = cell_work_;
  if (!scene_.effects.energy_tracking) {
    // Not tracked: the contacts' channels are unknown, not zero, and so are the total and the
    // balance error; kinetic and potential energy (the at-rest test) stay.
    const double unknown = std::numeric_limits<double>::quiet_NaN();
    for (double* c : {&b.elastic_normal, &b.elastic_tangential, &b.elastic_rolling, &b.dissipated_damping,
                      &b.dissipated_friction, &b.tangential_stiffness_change, &b.dissipated_rolling,
                      &b.rolling_stiffness_change, &b.work_by_walls})
      *c = unknown;
  }
  return b;
}

void Simulation::follow_cell_stress() {
  // The Love-Weber average over the cell with its kinetic part (cell_stress.h).
  const Box& box = decomposition().cell().box;
  const double volume = (box.hi - box.lo).prod();
  const Mat3 sigma_volume = cell_stress_times_volume(p_, n_owned_, out_.contacts, summation_, comm());
  const Mat3 sigma = sigma_volume / volume;
  // The cell's work over the step by the trapezoidal rule, with the L of the step: the
  // power V sigma : L at its two ends (docs/periodic.md, "The cell's work").
  if (cell_stress_known_)
    cell_work_ += 0.5 * dt_ * ((cell_stress_volume_ + sigma_volume).cwiseProduct(cell_l_)).sum();
  cell_stress_known_ = true;
  cell_stress_volume_ = sigma_volume;
  cell_stress_ = sigma;
  if (!cell_held_) set_cell_velocity_gradient(updated_velocity_gradient(scene_.cell, cell_l_, sigma));
}

void Simulation::hold_cell(bool held) {
  if (!deforming_ || held == cell_held_) return;
  if (held) cell_l_before_hold_ = cell_l_;
  set_cell_velocity_gradient(held ? Mat3::Zero() : cell_l_before_hold_);
  cell_held_ = held;
}

void Simulation::set_cell_velocity_gradient(const Mat3& l) {
  if (l == cell_l_) return;
  cell_l_ = l;
  cell_flow_ = mean_flow(cell_l_, scene_.cell.shear);
}

std::vector<Vec3> Simulation::wall_forces() const { return wall_loads().force; }

Simulation::WallLoads Simulation::wall_loads() const {
  if (restored_wall_loads_) return *restored_wall_loads_;
  // The force, then the dashpot's part of it, three components per wall each.
  const std::size_t k = 3 * walls_.size();
  const bool damping = !out_.wall_damping.empty();
  std::vector<double> total(2 * k, 0.0);
  if (summation_ == Summation::deterministic) {
    // Per wall, the exact sum of its entries' forces (exact_sum.h): the same bits on any rank
    // count, one message of every wall's digits.
    std::vector<ExactSum> sums(2 * k);
    const WallList& entries = lists_->walls();
    for (std::size_t e = 0; e < entries.size(); ++e) {
      const std::size_t w = 3 * static_cast<std::size_t>(entries.wall[e]);
      for (int d = 0; d < 3; ++d) {
        sums[w + d].add(-out_.wall_force[e][d]);
        if (damping) sums[k + w + d].add(-out_.wall_damping[e][d]);
      }
    }
    ExactSum::reduce(sums, comm());
    for (std::size_t c = 0; c < sums.size(); ++c) total[c] = sums[c].value();
  } else {
    for (std::size_t w = 0; w < walls_.size(); ++w) {
      put(total.data() + 3 * w, out_.wall_force[w]);
      if (damping) put(total.data() + k + 3 * w, out_.wall_damping[w]);
    }
    if (ranks() > 1)
      MPI_Allreduce(MPI_IN_PLACE, total.data(), static_cast<int>(total.size()), MPI_DOUBLE, MPI_SUM, comm());
  }
  WallLoads out{std::vector<Vec3>(walls_.size()), std::vector<Vec3>(walls_.size())};
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    out.force[w] = get(total.data() + 3 * w);
    out.damping[w] = get(total.data() + k + 3 * w);
  }
  return out;
}

Simulation::WallWorkAhead Simulation::wall_work_ahead(const WallLoads& loads) const {
  // The force loop books, at each evaluation, the coming step's half of the walls' work and of
  // the dashpot's wall part at the walls' present velocities (force_loop_body.h).
  WallWorkAhead ahead;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    ahead.work -= 0.5 * dt_ * loads.force[w].dot(walls_[w].velocity);
    ahead.damping -= 0.5 * dt_ * loads.damping[w].dot(walls_[w].velocity);
  }
  return ahead;
}

StepDiagnostics Simulation::diagnostics() const {
  long counts[2] = {out_.pair_contacts, out_.wall_contacts};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG, MPI_SUM, comm());
  double overlap = last_overlap_ratio_;
  MPI_Allreduce(MPI_IN_PLACE, &overlap, 1, MPI_DOUBLE, MPI_MAX, comm());
  // step() checks each evaluation at the next step's reduction; this covers a run's last one.
  check_overlap(overlap);
  StepDiagnostics d;
  d.particle_contacts = counts[0];
  d.wall_contacts = counts[1];
  d.max_overlap_ratio = overlap;
  d.neighbor_builds = rebuilds_;
  const ContactSolverStats& s = solver_stats_;
  std::int64_t c[9] = {s.calls,    s.warm_starts, s.warm_rejected, s.newton_iterations, s.fallbacks,
                       s.failures, s.uncertified, s.proven_apart,  s.still_apart};
  MPI_Allreduce(MPI_IN_PLACE, c, 9, MPI_INT64_T, MPI_SUM, comm());
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

RankDiagnostics Simulation::rank_diagnostics() const {
  RankDiagnostics d;
  d.particles = n_global_;
  d.owned = n_owned_;
  d.ghosts = static_cast<long>(p_.size()) - n_owned_;
  d.pair_slots = static_cast<long>(lists_->pairs().num_pairs());
  d.rebuilds = rebuilds_;
  d.migrated_out = domain_->migrated_out();
  d.max_overlap_ratio = last_overlap_ratio_;
  const BalanceRecord& b = domain_->balance();
  d.rebalances = b.count;
  d.rebalance_step = b.last_step;
  d.imbalance_before = b.before;
  d.imbalance_after = b.after;
  return d;
}

LoadImbalance Simulation::load_imbalance() const {
  const double mine[3] = {static_cast<double>(n_owned_), static_cast<double>(lists_->pairs().num_pairs()),
                          timings_.compute()};
  double max[3] = {0, 0, 0}, sum[3] = {0, 0, 0};
  MPI_Allreduce(mine, max, 3, MPI_DOUBLE, MPI_MAX, comm());
  MPI_Allreduce(mine, sum, 3, MPI_DOUBLE, MPI_SUM, comm());
  LoadImbalance b;
  b.ranks = ranks();
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

EngineLoad Simulation::load() const {
  const LoadImbalance b = load_imbalance();
  double share = timings_.total() > 0.0 ? timings_.communication() / timings_.total() : 0.0;
  MPI_Allreduce(MPI_IN_PLACE, &share, 1, MPI_DOUBLE, MPI_MAX, comm());
  EngineLoad l;
  l.ranks = ranks();
  l.rebalances = domain_->balance().count;
  l.owned_imbalance = b.owned_ratio;
  l.compute_imbalance = b.compute_ratio;
  l.communication_share = share;
  return l;
}

}  // namespace upgrain::dem
