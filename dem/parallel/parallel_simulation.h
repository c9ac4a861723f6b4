#pragma once
// The MPI step loop: a Cartesian decomposition (decomposition.h; planes fixed or moved by the
// load balance, load_balance.h), ghosts over the 26 neighbours by the three-stage x/y/z
// exchange, migration with contact history at neighbour-list rebuilds, and a force sum
// whose result does not depend on the number of ranks, bit for bit (docs/parallel.md). The
// integrator is Simulation::step's velocity Verlet, operation for operation, with its
// rotation splitting for ellipsoids (docs/parallel.md, "Ellipsoids").
#include <mpi.h>

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "dem/boundary/plane_wall.h"
#include "dem/core/material.h"
#include "dem/core/particle_store.h"
#include "dem/energy.h"
#include "dem/parallel/contact_lists.h"
#include "dem/parallel/decomposition.h"
#include "dem/parallel/deterministic_forces.h"
#include "dem/parallel/load_balance.h"
#include "dem/parallel/parallel_stress.h"
#include "dem/parallel/records.h"
#include "dem/scene/scene_config.h"
#include "dem/simulation.h"

namespace upgrain::dem {

struct ParallelOptions {
  std::array<int, 3> blocks{0, 0, 0};  // {0,0,0}: chosen from the rank count and the box
  // The box the blocks divide; default: the container footprint, from the floor (or the
  // lowest particle) to the highest particle surface. Outer blocks are open outwards.
  std::optional<Box> box;
  // Load balance (docs/parallel.md, "Load balance"): at the first neighbour-list rebuild
  // at or after every `balance_interval` steps, the planes move to the quantiles of
  // `balance_cost` along each cut axis; with `balance_at_start` also at construction (a bed
  // at rest is never rebuilt). 0: fixed (Eulerian) blocks.
  long balance_interval = 0;
  BalanceCost balance_cost = BalanceCost::particles;
  bool balance_at_start = true;
};

struct ParallelDiagnostics {
  long particles = 0;              // global
  long owned = 0;                  // on this rank
  long ghosts = 0;                 // on this rank
  long pair_slots = 0;             // on this rank
  long rebuilds = 0;               // neighbour-list rebuilds (identical on every rank)
  long migrated_out = 0;           // particles this rank sent away, cumulative
  double max_overlap_ratio = 0.0;  // of the last evaluation, on this rank
  // Load balance (identical on every rank): the number of rebalances, the step of the last,
  // and max/mean over ranks of the balanced cost just before it and at the end of its
  // rebuild (after migration and the new lists). 1 = perfect balance.
  long rebalances = 0;
  long rebalance_step = -1;
  double imbalance_before = 1.0;
  double imbalance_after = 1.0;
};

// Wall-clock seconds spent by this rank in the parts of step(), accumulated since the end
// of construction (or reset_timings()): steady_clock reads, six per step and two per
// message phase of a rebuild, so the overhead is a few hundred nanoseconds per step.
struct ParallelTimings {
  long steps = 0;
  double integrate = 0.0;         // half kicks and drift of the owned particles
  double reduction = 0.0;         // the per-step MPI_Allreduce; includes waiting for the slowest rank
  double ghost_refresh = 0.0;     // ghost motion: packing, the three exchanges, unpacking
  double rebuild = 0.0;           // whole rebuilds: migration, ghosts, lists (compute and messages)
  double rebuild_messages = 0.0;  // the messages and reductions inside those rebuilds
  double forces = 0.0;            // force evaluation
  [[nodiscard]] double total() const { return integrate + reduction + ghost_refresh + rebuild + forces; }
  [[nodiscard]] double communication() const { return reduction + ghost_refresh + rebuild_messages; }
  [[nodiscard]] double compute() const { return total() - communication(); }
};

// Load balance over the ranks (collective; every rank receives the same numbers), for a
// log line: max/mean of the owned particles, of the pair slots (ghost pairs included),
// and of the compute seconds of ParallelTimings. A ratio is 1 for a perfect balance.
struct LoadImbalance {
  int ranks = 1;
  long owned_max = 0;
  double owned_mean = 0.0;
  double owned_ratio = 1.0;
  long pairs_max = 0;
  double pairs_mean = 0.0;
  double pairs_ratio = 1.0;
  double compute_max = 0.0;
  double compute_mean = 0.0;
  double compute_ratio = 1.0;
};

class ParallelSimulation {
 public:
  // Collective over `comm`. The particles of rank 0 are the scene (other ranks may pass
  // the same or an empty store); each rank keeps those in its block. Walls: the scene's
  // open box, or the given planes.
  ParallelSimulation(const SceneConfig& scene, const ParticleStore& particles, MPI_Comm comm,
                     const ParallelOptions& options = {});
  ParallelSimulation(const SceneConfig& scene, const ParticleStore& particles, std::vector<PlaneWall> walls,
                     MPI_Comm comm, const ParallelOptions& options = {});

  // Collective. Throws upgrain::Error on every rank (a lost or runaway particle, a
  // non-finite state, a particle count that changed).
  void step();
  void run(long steps);

  // Collective: the whole state sorted by global id on rank 0 (empty on the other ranks),
  // with the forces and torques of the last evaluation.
  [[nodiscard]] ParticleStore gather_sorted_by_id() const;
  // Collective: the rank that owns each particle, in the order of gather_sorted_by_id() (its
  // compute grid: the block that held its centroid at the last migration), on rank 0; empty
  // elsewhere.
  [[nodiscard]] std::vector<int> gather_owners_sorted_by_id() const;
  // The compute grids, block r of rank r (parallel_stress.h, compute_grid_blocks).
  [[nodiscard]] std::vector<Box> compute_grid_blocks() const;

  // Asks the next force evaluation (the next step()) to record the contacts of the owned
  // particles (DeterministicForceKernels::recording: local indices, pairs with a = the
  // lower id and the force on it); they stay valid until the following step.
  void request_contacts() { record_next_ = true; }
  [[nodiscard]] const std::vector<ContactSample>& contacts() const { return contacts_; }
  [[nodiscard]] bool contacts_recorded() const { return recorded_; }

  // Collective, after a step that recorded contacts (else upgrain::Error): the stress of a
  // fixed grid, bitwise the same on any rank count, and of the compute grids (one cell per
  // block). Every rank receives the result. docs/stress.md, "Stress in parallel".
  [[nodiscard]] GridStress grid_stress(const RegularGrid& grid) const;
  [[nodiscard]] ComputeGridStress compute_grid_stress() const;
  [[nodiscard]] GrainDynamics grain_dynamics() const { return {g_, rotation_}; }
  // Collective: every recorded contact once (pairs from the owner of their lower id), on
  // rank 0, sorted by key; empty elsewhere.
  [[nodiscard]] std::vector<ContactRecord> gather_contacts_by_id() const;

  // Collective; every rank receives the same numbers. Kinetic, potential and elastic
  // energies are summed per particle in global-id order (bitwise rank-independent); the
  // cumulative dissipation is a per-rank running sum reduced over ranks (rank-independent
  // to round-off, docs/parallel.md). All zero but kinetic and potential without the
  // energy_tracking effect.
  [[nodiscard]] EnergyBalance energy() const;
  // Collective: the force exerted by the particles on each wall at the last evaluation,
  // summed per wall in global-id order (bitwise rank-independent).
  [[nodiscard]] std::vector<Vec3> wall_forces() const;

  // Collective, the same on every rank: the energy at construction (the reference of the
  // balance error and of the energy released).
  [[nodiscard]] const EnergyBalance& initial_energy() const { return e0_; }
  // Kinetic energy taken out by a relaxation (parallel_relaxation.h); the caller passes the
  // same global value on every rank.
  void account_removed_kinetic_energy(double joules) { removed_by_relaxation_ += joules; }
  // Collective: the contact counts of the last evaluation over all ranks (each pair once),
  // its largest overlap ratio and the rebuilds so far; the same on every rank.
  [[nodiscard]] StepDiagnostics step_diagnostics() const;
  // Collective (every rank calls it at the same step): moves the wall far behind its own
  // plane, as Simulation::remove_wall, and rebuilds the lists. Throws if no wall has the name.
  void remove_wall(const std::string& name);
  [[nodiscard]] const std::vector<PlaneWall>& walls() const { return walls_; }
  // Collective: upgrain::Error on every rank if an owned particle has a non-finite state.
  void check_finite() const;
  [[nodiscard]] bool integrates_rotation() const { return rotation_; }
  [[nodiscard]] Vec3 gravity() const { return g_; }
  [[nodiscard]] MPI_Comm comm() const { return comm_; }
  // Owned velocities and angular velocities may be changed between steps (a relaxation);
  // the ghosts receive them at the next step. Nothing else may change.
  [[nodiscard]] ParticleStore& local_particles_for_update() { return p_; }

  [[nodiscard]] const Decomposition& decomposition() const { return *decomp_; }
  // Owned particles are p[0, owned()); ghosts follow.
  [[nodiscard]] const ParticleStore& local_particles() const { return p_; }
  [[nodiscard]] int owned() const { return n_owned_; }
  [[nodiscard]] long step_count() const { return step_; }
  [[nodiscard]] double time() const { return step_ * dt_; }
  [[nodiscard]] double interaction_range() const { return range_; }
  [[nodiscard]] ParallelDiagnostics diagnostics() const;
  [[nodiscard]] const ParallelTimings& timings() const { return timings_; }
  void reset_timings() { timings_ = {}; }
  // Collective.
  [[nodiscard]] LoadImbalance load_imbalance() const;

 private:
  void rebuild();
  void migrate();
  void migration_pass();
  // Load balance (rebalance.cc): moves the planes when due, before migration; measures
  // the balance once the rebuild that moved them is complete.
  bool rebalance_if_due();
  void measure_balance_after();
  [[nodiscard]] long owned_cost(int i) const;
  void build_ghosts();
  void refresh_ghosts();
  void sort_owned_by_cell();
  void evaluate_forces();
  static double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  SceneConfig scene_;
  std::vector<PlaneWall> walls_;
  std::unique_ptr<Decomposition> decomp_;
  MPI_Comm comm_ = MPI_COMM_NULL;  // the Cartesian communicator
  ParticleStore p_;
  int n_owned_ = 0;
  long n_global_ = 0;
  double max_radius_ = 0.0;
  double skin_ = 0.0;
  double range_ = 0.0;  // largest diameter + skin
  Vec3 g_ = Vec3::Zero();
  double dt_ = 0.0;
  bool rotation_ = false;
  // Ellipsoids (docs/parallel.md, "Ellipsoids"): shape records travel next to the state
  // records, contact memory next to the springs; the same on every rank (rank 0's scene).
  bool shapes_ = false;
  long step_ = 0;
  long rebuilds_ = 0;
  long migrated_out_ = 0;
  double last_overlap_ratio_ = 0.0;
  long last_overlap_step_ = 0;
  long last_pair_contacts_ = 0;  // pairs whose lo is owned
  long last_wall_contacts_ = 0;
  EnergyBalance e0_;
  double removed_by_relaxation_ = 0.0;
  ParallelTimings timings_;

  ContactLists lists_;
  DeterministicForceKernels kernels_{};
  bool energy_tracking_ = false;
  bool record_next_ = false;
  bool recorded_ = false;
  std::vector<ContactSample> contacts_;
  OwnedEnergyTerms energy_terms_;
  // Cumulative dissipation on this rank (owned walls, pairs whose lo is owned).
  double dissipated_damping_ = 0.0;
  double dissipated_friction_ = 0.0;
  double stiffness_change_ = 0.0;
  ContactMaterial material_;
  std::vector<Vec3> x_at_build_;
  std::vector<SpringRecord> history_;
  std::vector<MemoryRecord> memory_history_;
  GrainPoses posed_;
  ContactSolverStats solver_stats_;  // this rank's, cumulative
  struct {
    long interval = 0;
    BalanceCost cost = BalanceCost::particles;
    long next_step = 0;
    long count = 0;
    long last_step = -1;
    double before = 1.0, after = 1.0;
    bool measure_after = false;
    std::vector<long> histogram, reduced;  // 3 axes x kBalanceBins, then the total cost
  } balance_;

  // Ghost routes of the current rebuild, per axis and face: the local indices sent and
  // where the received ghosts start in the store. Refreshes follow the same routes.
  std::array<std::array<std::vector<int>, 2>, 3> ghost_send_;
  std::array<std::array<int, 2>, 3> ghost_recv_start_{};
  std::array<std::array<int, 2>, 3> ghost_recv_count_{};
  // Message buffers, kept between steps.
  std::array<std::vector<GhostRecord>, 2> ghost_out_, ghost_in_;
  std::array<std::vector<MotionRecord>, 2> motion_out_, motion_in_;
  std::array<std::vector<StateRecord>, 2> state_out_, state_in_;
  std::array<std::vector<SpringRecord>, 2> spring_out_, spring_in_;
  std::array<std::vector<ShapeRecord>, 2> shape_out_, shape_in_;
  std::array<std::vector<OrientationRecord>, 2> orientation_out_, orientation_in_;
  std::array<std::vector<MemoryRecord>, 2> memory_out_, memory_in_;
};

// Gathered contacts as ContactSamples indexing a store sorted by id (gather_sorted_by_id):
// what the serial grid_stress() takes.
std::vector<ContactSample> contacts_in_store(const std::vector<ContactRecord>& contacts,
                                             const ParticleStore& sorted_by_id);

}  // namespace upgrain::dem
