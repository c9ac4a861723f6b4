#pragma once
// Grid stress in a parallel run (docs/stress.md, "Stress in parallel"), by all seven
// formulas, from the contacts a rank recorded in one evaluation (dem/engine/force_loop.h) and
// its local store (owned particles first, then ghosts). One pair of functions per summation
// (dem/engine/summation.h).
//
// Deterministic summation (parallel_grid_stress, parallel_compute_grid_stress): every rank
// has recorded every contact of its owned particles, a pair across two ranks on both.
// Every owned ("black") particle p contributes its own share of its cell, summed over its
// contacts in a canonical order (walls by index, then partners by global id):
//  - Bagi: sum_c f^pc (x) (x^c - x^p) over all its contacts; over the particles of a cell
//    this is the internal + external classification of grid_stress();
//  - Weber: f (x) (x^q - x^p) for a partner q in the same cell, counted by the lower id of
//    the two, so once per internal contact;
//  - Drescher and De Saxce: its external contacts (partner outside the cell, or a wall),
//    the body term and the inertial moment D.
// A partner that is a ghost ("green") is classified by its own centroid, which is the
// same bits on every rank. The per-particle shares are then summed per cell in global-id
// order, so the result does not depend on the number of ranks, bit for bit.
#include <mpi.h>

#include <vector>

#include "dem/contact/contact_sample.h"
#include "dem/core/particle_store.h"
#include "dem/parallel/decomposition.h"
#include "dem/stress/grid_stress.h"

namespace upgrain::dem {

// One owned particle's share of one cell (cell = -1: outside the grid).
struct ParticleStressShare {
  GlobalId gid = 0;
  int cell = -1;
  StressSums sums;
};

// The shares of the owned particles, from the recorded contacts. cell_of_local[i] is the
// cell of local particle i (owned or ghost), centre[c] the reference point of cell c for
// De Saxce's terms.
std::vector<ParticleStressShare> particle_stress_shares(const ParticleStore& local, int n_owned,
                                                        const std::vector<ContactSample>& contacts,
                                                        const std::vector<int>& cell_of_local,
                                                        const std::vector<Vec3>& centre,
                                                        const GrainDynamics& dynamics);

// A fixed user grid, independent of the rank count: collective over `comm`; every rank
// receives the same GridStress. The shares are gathered on rank 0, summed per cell in
// global-id order, and the cell sums broadcast.
// In a periodic `cell`, grains are put into grid cells by their wrapped positions (an image
// belongs to its grain's cell) and contacts keep their minimum-image branch vectors.
GridStress parallel_grid_stress(const ParticleStore& local, int n_owned,
                                const std::vector<ContactSample>& contacts, const RegularGrid& grid,
                                const GrainDynamics& dynamics, MPI_Comm comm, const PeriodicCell& cell = {});

// The compute grids (one block per rank), block r at index r, clipped to the decomposition
// box (the outer blocks are open). Not collective: every rank knows the planes.
std::vector<Box> compute_grid_blocks(const Decomposition& decomposition);

// The compute grids: each rank's block is one cell holding its owned particles
// (black-black contacts internal, black-green external with the force on the black
// particle, walls external). Cell r is rank r's block, clipped to the decomposition box
// (the outer blocks are open); GridStress::volume holds the clipped volumes, `block` the
// clipped blocks. Collective; every rank receives all blocks.
ComputeGridStress parallel_compute_grid_stress(const ParticleStore& local, int n_owned,
                                               const std::vector<ContactSample>& contacts,
                                               const Decomposition& decomposition,
                                               const GrainDynamics& dynamics);

// Fast summation: every contact was recorded once over the ranks (by the rank that evaluated
// it). Each rank sums its contacts and owned particles per cell (cell_stress_sums, as
// grid_stress() does on one rank, so one rank gives grid_stress() bit for bit) and the cell
// sums are added over the ranks (MPI_SUM): the result depends on the decomposition to
// round-off. For the compute grids a ghost belongs to its owner's block (`owner[i]` for every
// local particle i).
GridStress summed_grid_stress(const ParticleStore& local, int n_owned,
                              const std::vector<ContactSample>& contacts, const RegularGrid& grid,
                              const GrainDynamics& dynamics, MPI_Comm comm, const PeriodicCell& cell = {});
ComputeGridStress summed_compute_grid_stress(const ParticleStore& local, int n_owned,
                                             const std::vector<ContactSample>& contacts,
                                             const Decomposition& decomposition,
                                             const std::vector<int>& owner, const GrainDynamics& dynamics);

}  // namespace upgrain::dem
