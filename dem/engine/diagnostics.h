#pragma once
// What the engine reports of its own work besides the physics: contact counts, list
// rebuilds, the load of each rank and the time spent in each part of a step.
#include <cstdint>

#include "dem/contact/ellipsoid_geometry.h"

namespace upgrain::dem {

// Over all ranks, the same on every rank (collective).
struct StepDiagnostics {
  long particle_contacts = 0;  // touching pairs of the last evaluation, each once
  long wall_contacts = 0;
  double max_overlap_ratio = 0.0;  // of the last evaluation
  long neighbor_builds = 0;
  // Ellipsoid contact solver, cumulative (zero for spheres), summed over ranks: with
  // deterministic summation a pair across two ranks is solved on both.
  ContactSolverStats contact_solver;
};

// This rank's share (not collective).
struct RankDiagnostics {
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

// Wall-clock seconds spent by this rank in the parts of step(), accumulated since the end of
// construction (or reset_timings()): steady_clock reads, seven per step and two per message
// phase of a rebuild, so the overhead is a few hundred nanoseconds per step.
struct StepTimings {
  long steps = 0;
  double integrate = 0.0;         // half kicks and drift of the owned particles
  double reduction = 0.0;         // the per-step MPI_Allreduce; includes waiting for the slowest rank
  double ghost_refresh = 0.0;     // ghost motion, and (fast summation) the ghost forces returned
  double rebuild = 0.0;           // whole rebuilds: migration, ghosts, lists (compute and messages)
  double rebuild_messages = 0.0;  // the messages and reductions inside those rebuilds
  double forces = 0.0;            // force evaluation
  [[nodiscard]] double total() const { return integrate + reduction + ghost_refresh + rebuild + forces; }
  [[nodiscard]] double communication() const { return reduction + ghost_refresh + rebuild_messages; }
  [[nodiscard]] double compute() const { return total() - communication(); }
};

// Load balance over the ranks (collective; every rank receives the same numbers), for a log
// line: max/mean of the owned particles, of the pair slots (ghost pairs included), and of
// the compute seconds of StepTimings. A ratio is 1 for a perfect balance.
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

// How the work was shared among the ranks (for the log and summary.json).
struct EngineLoad {
  int ranks = 1;
  long rebalances = 0;               // moves of the block planes (docs/parallel.md, "Load balance")
  double owned_imbalance = 1.0;      // max/mean of the particles owned per rank, now
  double compute_imbalance = 1.0;    // max/mean of the compute seconds per rank
  double communication_share = 0.0;  // largest share of a rank's step time spent in messages
};

}  // namespace upgrain::dem
