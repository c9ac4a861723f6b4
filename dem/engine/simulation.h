#pragma once
// The DEM engine: one step loop for any number of MPI ranks, one rank included
// (docs/architecture.md). Each rank owns the particles of its block of a Cartesian
// decomposition and holds ghosts of its neighbours' (dem/parallel/domain.h); one force loop
// (force_loop.h) evaluates every contact of the neighbour lists (dem/neighbor/verlet_list.h),
// whose histories live in one store (dem/core/contact_history.h); the integrator is velocity
// Verlet for translation and rotation (docs/integrator.md), with the symplectic splitting of
// rigid_rotation.h for ellipsoids. The summation (summation.h) decides the order of every sum:
// with the default, deterministic, the particle states and every output are bitwise the same
// on any number of ranks.
//
// Every method is collective over the engine's communicator unless it says otherwise: every
// rank calls it at the same point of the run. Errors (a non-finite state, a runaway overlap,
// a lost particle) are thrown as upgrain::Error on every rank (guards.h).
#include <mpi.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dem/contact/contact_sample.h"
#include "dem/core/box.h"
#include "dem/core/contact_history.h"
#include "dem/core/material.h"
#include "dem/core/particle_store.h"
#include "dem/core/plane_wall.h"
#include "dem/engine/diagnostics.h"
#include "dem/engine/energy.h"
#include "dem/engine/engine_state.h"
#include "dem/engine/force_loop.h"
#include "dem/engine/summation.h"
#include "dem/neighbor/verlet_list.h"
#include "dem/parallel/domain.h"
#include "dem/parallel/exact_sum.h"
#include "dem/parallel/records.h"
#include "dem/scene/insertion.h"
#include "dem/scene/scene_config.h"
#include "dem/scene/weight_overlap.h"
#include "dem/stress/grid_stress.h"

namespace upgrain::dem {

// The domain decomposition's blocks and load balance (DomainOptions), and:
struct EngineOptions : DomainOptions {
  Summation summation = Summation::deterministic;
  // The box the blocks divide; default: the container footprint, from the floor (or the
  // lowest particle) to the highest particle surface. Outer blocks are open outwards.
  std::optional<Box> box;
};

// Largest overlap (as a fraction of the smallest semi-axis) tolerated before the run stops:
// beyond it the contact law is far outside its validity and the step is too large.
inline constexpr double kRunawayOverlapRatio = 0.25;

// How far behind its plane remove_wall() puts a wall: every grain is then at a distance of
// order 1e100 inside the domain, and no contact can form (distance() stays finite).
inline constexpr double kRemovedWallDistance = 1e100;

// A rank's rows of an id-sorted whole (Simulation::whole_state_slice()).
struct IdSlice {
  // Rows first_row .. first_row + rows - 1, sorted by id; after them the grains of other rows
  // that Simulation::add_other_rows() brought, sorted by id.
  ParticleStore grains;
  long first_row = 0;
  std::size_t rows = 0;
  long total_rows = 0;  // the whole's
  bool shapes = false;  // the scene's grains have shapes (also when this slice is empty)
};

class Simulation {
 public:
  // The particles of rank 0 are the scene (other ranks may pass the same or an empty store);
  // each rank keeps those in its block (on one rank, the store itself: move it in to save a
  // copy). Walls: the scene's open box, or the given planes. Evaluates the initial forces.
  Simulation(const SceneConfig& scene, ParticleStore particles, MPI_Comm comm = MPI_COMM_SELF,
             const EngineOptions& options = {});
  Simulation(const SceneConfig& scene, ParticleStore particles, std::vector<PlaneWall> walls,
             MPI_Comm comm = MPI_COMM_SELF, const EngineOptions& options = {});
  // `Simulation(scene, particles, {})` would pass a null communicator (MPI_Comm is a pointer):
  // refused, so that "no walls" is written std::vector<PlaneWall>{}.
  Simulation(const SceneConfig&, const ParticleStore&, std::nullptr_t) = delete;

  // Continues a run from a state captured by capture_state() (collective; `state` is read on
  // rank 0, other ranks may pass an empty one), on any number of ranks: the scene must be the
  // one it was captured with. Nothing is evaluated: the next step() is the step that followed
  // the capture, and with the deterministic summation it gives the same bits
  // (docs/restart.md).
  Simulation(const SceneConfig& scene, const EngineState& state, MPI_Comm comm = MPI_COMM_SELF,
             const EngineOptions& options = {});
  // The state between two steps, gathered on rank 0 (empty elsewhere). Collective.
  [[nodiscard]] EngineState capture_state() const;
  // The options the engine was made with (a restored engine's: the box and balance of its
  // state), to make another engine of the same run from a captured state.
  [[nodiscard]] const EngineOptions& options() const { return options_; }

  void step();
  void run(long steps);

  // --- Insertion during the run (docs/insertion.md; dem/engine/pour.h decides what and when).
  // Adds grains between two steps, from the next step on: `grains` is the same on every rank
  // (their ids particle_count(), particle_count() + 1, ...), each rank keeps those whose centroid
  // is in its block, and the next step integrates them with the others and rebuilds the lists,
  // which joins them. The caller guarantees they overlap nothing (their force is zero until that
  // evaluation). The energy balance's reference takes their kinetic and potential energy, so
  // the balance stays closed, and the lost-particle guard their count and mass. A scene whose
  // insertion is on already sized the interaction range and shapes for them (set_up). Collective.
  void insert(const ParticleStore& grains);
  // The owned grains whose bounding sphere (radius; for an ellipsoid its major semi-axis) reaches
  // into `box`, from every rank, sorted by id: the same on every rank. Collective.
  [[nodiscard]] std::vector<BoundingSphere> bounding_spheres_in(const Box& box) const;

  // --- State.
  // This rank's particles: the owned ones [0, owned()), then the ghosts. Not collective.
  // Owned velocities and angular velocities may be changed between steps (a relaxation); the
  // ghosts receive them at the next step.
  [[nodiscard]] const ParticleStore& particles() const { return p_; }
  [[nodiscard]] ParticleStore& particles() { return p_; }
  [[nodiscard]] int owned() const { return n_owned_; }
  [[nodiscard]] long particle_count() const { return n_global_; }  // not collective
  // The whole state sorted by global id on rank 0 (empty elsewhere), with the forces and
  // torques of the last evaluation.
  [[nodiscard]] ParticleStore gather_sorted_by_id() const;
  // The same, checked (guards.h: no particle lost or doubled, the mass unchanged since the
  // first call) and kept until the next call or step; the reference is valid on rank 0.
  [[nodiscard]] const ParticleStore& whole_state();
  // This rank's rows of the whole state sorted by id, for output that every rank writes its
  // share of (docs/parallel.md, "Output"): the grains of ids first_row(n, r, P) ..
  // first_row(n, r + 1, P) - 1 (exchange.h), sent by their owners (one all-to-all), sorted by
  // id. Checked as whole_state() is, with the same mass summed in id order (continued from
  // rank to rank) and the same reference: a slice that does not hold exactly its rows' ids
  // stops the run on every rank. No rank holds more than its share. Collective.
  [[nodiscard]] IdSlice whole_state_slice();
  // Appends to slice.grains, after its rows, the grains of `wanted` (ids sorted and unique, none
  // of them in this rank's rows) from the ranks whose rows hold them: a rank's share of an
  // output that refers to grains of other rows (the force network's partners). Two all-to-alls.
  // Collective.
  void add_other_rows(IdSlice& slice, const std::vector<GlobalId>& wanted) const;
  // The rank that owns each particle, in the order of gather_sorted_by_id() (its compute
  // grid: the block that held its centroid at the last migration), on rank 0.
  [[nodiscard]] std::vector<int> gather_owners_sorted_by_id() const;
  // The compute grids, block r of rank r, clipped to the decomposition box. Not collective.
  [[nodiscard]] std::vector<Box> compute_grid_blocks() const;

  // --- The scene. Not collective, except set_gravity(), add_wall(), remove_wall() and
  // set_wall_velocity(), which every rank calls alike.
  [[nodiscard]] const SceneConfig& scene() const { return scene_; }
  [[nodiscard]] Summation summation() const { return summation_; }
  // The effects the chosen force loop was compiled with (dem/engine/force_loop.h).
  [[nodiscard]] const EffectSet& force_loop_effects() const { return loops_.compiled; }
  [[nodiscard]] double time() const { return static_cast<double>(step_) * dt_; }
  [[nodiscard]] long step_count() const { return step_; }
  [[nodiscard]] double time_step() const { return dt_; }
  [[nodiscard]] Vec3 gravity() const { return g_; }
  // Any direction of gravity (an incline is a tilted gravity over a flat floor). Resets the
  // energy reference, since the potential energy is -m g.x.
  void set_gravity(const Vec3& g);
  // Whether rotation is integrated (EffectSet::integrates_rotation).
  [[nodiscard]] bool integrates_rotation() const { return rotation_; }
  [[nodiscard]] GrainDynamics grain_dynamics() const { return {g_, rotation_}; }
  [[nodiscard]] const std::vector<PlaneWall>& walls() const { return walls_; }
  // Takes a wall out of the scene (the collapse's gate and side walls): it is moved far
  // behind its own plane, and the next step() rebuilds the lists before it evaluates forces,
  // so no contact with it remains. Throws when no wall has that name.
  void remove_wall(const std::string& name);
  // Whether a wall was taken out by remove_wall() (it stays in walls(), far behind its plane).
  [[nodiscard]] bool wall_removed(std::size_t wall) const {
    return walls_.at(wall).distance(Vec3::Zero()) > 0.5 * kRemovedWallDistance;
  }
  // Puts a wall into the scene (a lid, a piston); its entries come with the next step's
  // rebuild. Names are unique: throws when the name is taken.
  void add_wall(const PlaneWall& wall);
  // The index of the wall of that name in walls() and wall_forces(); throws when there is none.
  [[nodiscard]] std::size_t wall_index(const std::string& name) const;
  // Sets a wall's rigid translation (m/s) from the next step on: step() moves its point by
  // dt v, the contacts see v as the wall's velocity, and its work enters the energy balance
  // (EnergyBalance::work_by_walls, by the trapezoidal rule of velocity Verlet). A wall that has
  // moved half a skin since the last build rebuilds the lists, as a particle does. Collective.
  void set_wall_velocity(std::size_t wall, const Vec3& velocity);

  // --- Contacts and stress.
  // Asks the next force evaluation (the next step()) to record its contacts (ForceOutput::
  // contacts, local indices); they stay valid until the following step. Call it on every
  // rank: the stress functions below are collective and refuse a step that did not record.
  void request_contacts() { record_next_ = true; }
  [[nodiscard]] const std::vector<ContactSample>& contacts() const { return out_.contacts; }
  // Bytes of per-contact and per-particle state that the chosen effects add and each
  // evaluation reads and writes: the contact-history store and the force loop's energy and
  // damping arrays (for the effect cost benchmark, bench/effect_cost.cc).
  [[nodiscard]] std::size_t effect_state_bytes() const {
    std::size_t b = history_.bytes();
    for (const auto* v : {&out_.damping_force, &out_.damping_torque, &out_.rolling_damping_torque})
      b += v->size() * sizeof(Vec3);
    b += out_.particle_elastic.size() * sizeof(ElasticEnergy) +
         dissipation_share_.size() * sizeof(DissipatedEnergy);
    return b;
  }
  [[nodiscard]] bool contacts_recorded() const { return recorded_; }
  // Every recorded contact once, on rank 0, sorted by key (a < b, force on a; or wall w as
  // b = -1 - w); empty elsewhere. `walls_only`: the wall contacts alone, chosen before they are
  // sent (a few hundred of a bed's many pair contacts).
  [[nodiscard]] std::vector<ContactRecord> gather_contacts_by_id(bool walls_only = false) const;
  // The same contacts spread over the ranks by their first grain: this rank's are those whose
  // a is in its rows of whole_state_slice(), sorted by key, so that the ranks' lists in rank
  // order are gather_contacts_by_id()'s. One all-to-all; no rank holds more than its rows'
  // contacts. Collective.
  [[nodiscard]] std::vector<ContactRecord> contacts_by_id_slice() const;
  // A rank's share of an output of the contacts (the force network): contacts_by_id_slice(),
  // and the grains of other rows that its pairs reach appended to `slice` (add_other_rows()).
  // Collective.
  [[nodiscard]] std::vector<ContactRecord> contacts_of_rows(IdSlice& slice) const;
  // After a step that recorded contacts (else upgrain::Error): the stress of a fixed grid and
  // of the compute grids (one cell per block), on every rank (docs/stress.md, "Stress in
  // parallel"). Deterministic summation: bitwise the same on any rank count.
  [[nodiscard]] GridStress grid_stress(const RegularGrid& grid) const;
  [[nodiscard]] ComputeGridStress compute_grid_stress() const;

  // --- A deforming periodic cell (docs/periodic.md, "A cell that deforms"; SceneConfig::cell).
  [[nodiscard]] bool cell_deforms() const { return deforming_; }
  // The cell matrix h (its lengths on the diagonal) and the corner it is spanned from.
  [[nodiscard]] Mat3 cell_matrix() const { return dem::cell_matrix(decomposition().cell()); }
  // The velocity gradient L of the coming step (h' = L h; the servo's after the last
  // evaluation).
  [[nodiscard]] const Mat3& cell_velocity_gradient() const { return cell_l_; }
  // A deforming cell held still (L = 0, the servos off) or let go again with the L it had: a
  // relaxation to equilibrium (relaxation.h) runs in the cell where the run stopped. Every
  // rank alike; nothing for a fixed cell.
  void hold_cell(bool held);
  // The cell's stress at the end of the last step, tension positive: the Love-Weber average
  // (1/V) sum f (x) l over the contacts (minimum-image branches, each pair once) plus the
  // kinetic part -(1/V) sum m u (x) u of the peculiar velocities u = v - L x. The same on every
  // rank; deterministic summation: the same bits on any rank count. Zero unless the cell
  // deforms.
  [[nodiscard]] const Mat3& cell_stress() const { return cell_stress_; }

  // --- Energy (docs/integrator.md), the same on every rank.
  [[nodiscard]] EnergyBalance energy() const;
  [[nodiscard]] const EnergyBalance& initial_energy() const { return e0_; }
  // (E_total(t) - E_total(0)) / (initial kinetic energy + |potential energy released|).
  [[nodiscard]] double energy_balance_error() const { return balance_error(e0_, energy()); }
  // Kinetic energy over the potential energy released since the start: the measure of a bed
  // at rest. Infinity while no potential energy has been released.
  [[nodiscard]] double kinetic_to_released() const { return dem::kinetic_to_released(e0_, energy()); }
  // Books kinetic energy that a caller removed by changing velocities (relaxation), so the
  // balance stays closed; the same global value on every rank. Not collective.
  void account_removed_kinetic_energy(double joules) { removed_by_relaxation_ += joules; }
  // The force exerted by the particles on each wall at the last evaluation.
  [[nodiscard]] std::vector<Vec3> wall_forces() const;

  // --- Guards (guards.h).
  // upgrain::Error on every rank, naming the particle, if an owned particle has a non-finite
  // position, velocity, angular velocity or orientation.
  void check_finite() const;

  // --- Ranks, load and diagnostics.
  [[nodiscard]] MPI_Comm comm() const { return domain_->comm(); }
  [[nodiscard]] int rank() const { return domain_->rank(); }
  [[nodiscard]] int ranks() const { return domain_->size(); }
  [[nodiscard]] bool is_root() const { return domain_->rank() == 0; }
  // Runs `work` on rank 0; an exception there is thrown on every rank.
  void on_root(const std::function<void()>& work) const;
  [[nodiscard]] const Decomposition& decomposition() const { return domain_->decomposition(); }
  [[nodiscard]] double interaction_range() const { return range_; }
  // The contact counts of the last evaluation over all ranks (each pair once), its largest
  // overlap ratio and the rebuilds so far.
  [[nodiscard]] StepDiagnostics diagnostics() const;
  [[nodiscard]] RankDiagnostics rank_diagnostics() const;  // not collective
  [[nodiscard]] const StepTimings& timings() const { return timings_; }
  void reset_timings() { timings_ = {}; }
  [[nodiscard]] LoadImbalance load_imbalance() const;
  [[nodiscard]] EngineLoad load() const;
  // This rank's ellipsoid contact solver counters since the start. Not collective.
  [[nodiscard]] const ContactSolverStats& contact_solver_stats() const { return solver_stats_; }

 private:
  // What every constructor sets up from the scene and the whole set of particles (`count`
  // grains, the largest of radius `max_radius`): shapes, rotation, the force loops, the
  // history kinds, the interaction range, the domain on `box` and the lists.
  void set_up(long count, double max_radius, bool shapes, const Box& box, MPI_Comm comm,
              const EngineOptions& options);
  void rebuild();
  void evaluate_forces();
  // The runaway-overlap guard (guards.h) for the largest overlap ratio over the ranks: when it
  // exceeds the limit, every rank throws the diagnosis, naming the contact of the rank that
  // holds it. Collective (every rank has the same `global_max`).
  void check_overlap(double global_max) const;
  // The cell's mean stress, coordination and solid fraction for the guard's diagnosis
  // (collective; pressure 0 where the cell's stress is not followed).
  [[nodiscard]] AssemblyLoad assembly_load() const;
  [[nodiscard]] int owner_of_local(std::size_t i) const;
  static double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  SceneConfig scene_;
  EngineOptions options_;
  // A deforming periodic cell: its velocity gradient (the diagonal in use), its box at the last
  // rebuild (the lists' validity), its stress and V sigma at the last evaluation, and the
  // cumulative work (the same bits on every rank).
  bool deforming_ = false;
  Mat3 cell_l_ = Mat3::Zero();
  MeanFlow cell_flow_;  // L as the drift and the force loop take it (ForceInput::mean_flow)
  Box cell_start_;      // the box its grid was sized from (a checkpoint's CellRecord::start)
  Box cell_at_build_;
  double offset_at_build_ = 0.0;  // a sheared cell's offset at the last rebuild
  Mat3 cell_stress_ = Mat3::Zero();
  Mat3 cell_stress_volume_ = Mat3::Zero();
  double cell_work_ = 0.0;
  bool cell_stress_known_ = false;  // an evaluation before: the work's trapezoid has its first end
  // Sets the cell's stress after an evaluation (collective) and, with a servo, the next L.
  void follow_cell_stress();
  // L changes to `l`: the grains keep their peculiar velocities (v += (l - L) x), the cell
  // takes the new rate.
  void set_cell_velocity_gradient(const Mat3& l);
  bool cell_held_ = false;
  Mat3 cell_l_before_hold_ = Mat3::Zero();
  std::vector<PlaneWall> walls_;
  std::vector<Vec3> wall_points_at_build_;  // the walls' points when the lists were last built
  bool walls_move_ = false;                 // some wall has a velocity
  void note_wall_motion();                  // sets walls_move_ from the walls' velocities
  // The last evaluation's force on each wall and the dashpot's part of it: the same bits on
  // every rank. Collective.
  struct WallLoads {
    std::vector<Vec3> force, damping;
  };
  [[nodiscard]] WallLoads wall_loads() const;
  // Half a step of the walls' work on the grains and of the dashpot's wall part, at the walls'
  // present velocities: what an evaluation books ahead for the coming step.
  struct WallWorkAhead {
    double work = 0.0, damping = 0.0;
  };
  [[nodiscard]] WallWorkAhead wall_work_ahead(const WallLoads& loads) const;
  Summation summation_;
  Vec3 g_ = Vec3::Zero();
  double dt_ = 0.0;
  bool rotation_ = false;
  bool shapes_ = false;
  ContactMaterial material_;
  LawConstants law_constants_;  // the scene's law's own (dem/contact/contact_laws.h)
  RollingParameters rolling_;
  ForceLoops loops_{};

  std::unique_ptr<Domain> domain_;
  ParticleStore p_;
  int n_owned_ = 0;
  // Grains inserted before this step, owned here, integrated apart until this step's rebuild
  // joins them to p_ (insert()).
  ParticleStore arrivals_;
  bool arrivals_pending_ = false;  // on every rank: insert() was called since the last rebuild
  long n_global_ = 0;
  double max_radius_ = 0.0;
  double skin_ = 0.0;
  double range_ = 0.0;  // largest diameter + skin
  std::unique_ptr<VerletList> lists_;
  ContactHistory history_;
  GrainPoses posed_;
  ForceOutput out_;

  long step_ = 0;
  long rebuilds_ = 0;
  bool rebuild_pending_ = false;  // a wall was removed: rebuild at the next step (on every rank)
  bool record_next_ = false;
  bool recorded_ = false;
  double last_overlap_ratio_ = 0.0;
  GlobalId last_overlap_particle_ = -1, last_overlap_partner_ = -1;  // its contact (ForceOutput)
  std::optional<WallLoads> restored_wall_loads_;  // after a restore, until the first evaluation
  long last_overlap_step_ = 0;

  // Cumulative dissipation (docs/integrator.md), each channel the exact sum of its terms on this
  // rank (dem/parallel/exact_sum.h). Deterministic summation: each grain keeps its own share
  // since the last rebuild, summed step by step in its own order (`dissipation_share_`, by
  // local index), and adds it to the exact sums at the next rebuild, before grains change index
  // or rank; the totals over the ranks then do not depend on how many there are. Fast: each
  // evaluation's running sums go straight into the exact sums.
  enum Channel {
    kDamping,
    kFriction,
    kStiffnessChange,
    kRolling,
    kRollingStiffnessChange,
    kWallWork,
    kChannels
  };
  std::array<ExactSum, kChannels> dissipated_;
  std::vector<DissipatedEnergy> dissipation_share_;
  // Adds shares to the exact sums: the grains' at a rebuild, the rank's of an evaluation (fast).
  static void add_to(std::array<ExactSum, kChannels>& sums, const DissipatedEnergy& d);
  void settle_dissipation();
  [[nodiscard]] bool dissipation_per_grain() const {
    return summation_ == Summation::deterministic && scene_.effects.energy_tracking;
  }
  double removed_by_relaxation_ = 0.0;
  EnergyBalance e0_;
  ContactSolverStats solver_stats_;  // this rank's, cumulative
  StepTimings timings_;
  // The owned grains of every rank that `collect` brings here, sorted by id.
  template <class Collect>
  [[nodiscard]] ParticleStore collect_by_id(Collect collect) const;
  // This rank's share of the recorded contacts, each contact once over the ranks, with the
  // lower id first (gather_contacts_by_id()).
  [[nodiscard]] std::vector<ContactRecord> contact_records(bool walls_only) const;
  ParticleStore gathered_;        // whole_state()
  double reference_mass_ = -1.0;  // of the first whole_state() (rank 0)
};

// Gathered contacts (Simulation::gather_contacts_by_id) as ContactSamples indexing a store
// sorted by id (Simulation::gather_sorted_by_id): what grid_stress() takes.
std::vector<ContactSample> contacts_in_store(const std::vector<ContactRecord>& contacts,
                                             const ParticleStore& sorted_by_id);

}  // namespace upgrain::dem
