#pragma once
// The stress of a periodic cell: the Love-Weber average over the cell with its kinetic part
// (Love 1927; Weber 1966; the kinetic term as in Evans & Morriss 1990, ch. 6),
//
//   V sigma = sum_c f_c (x) l_c  -  sum_i m_i u_i (x) u_i,
//
// f_c the force on the pair's first grain, l_c = x_second - x_first its minimum-image branch,
// u_i the peculiar velocity (docs/periodic.md, "The cell's stress"). Every pair counts once
// over the ranks: on the owner of its first grain (deterministic summation, where a pair
// across two ranks is evaluated on both) or on the rank that evaluated it (fast). Wall
// contacts are external to the cell and do not enter Weber's sum.
//
// The same value as grid_stress()'s Weber formula on one grid cell that is the cell, less the
// kinetic part (tests/parallel/deforming_cell_test.cc), without that machinery's per-grain shares,
// sorting and gather: it runs at every step of a deforming cell.
#include <mpi.h>

#include <vector>

#include "dem/contact/contact_sample.h"
#include "dem/core/particle_store.h"
#include "dem/engine/summation.h"

namespace upgrain::dem {

// Collective. `contacts`: one evaluation's recorded contacts (ForceOutput::contacts).
// Summed as `summation` asks (particle_sums.h): deterministic, the same bits on any rank count.
[[nodiscard]] Mat3 cell_stress_times_volume(const ParticleStore& p, int n_owned,
                                            const std::vector<ContactSample>& contacts, Summation summation,
                                            MPI_Comm comm);

}  // namespace upgrain::dem
