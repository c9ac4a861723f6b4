#pragma once
// FIRE relaxation to static equilibrium on the MPI engine: the algorithm of
// dem/relaxation.h (Bitzek et al. 2006) with its global sums (the power of the resultant
// forces and torques, the norms of the velocity mixing, the kinetic energy removed) taken
// by fixed-point sums (fixed_point_sum.h) and its residuals by MPI_MAX, so that the
// relaxed state is bitwise the same on any rank count. It is not bitwise the serial
// relax_to_equilibrium(Simulation&): the serial sums round in another order.
#include "dem/parallel/parallel_simulation.h"
#include "dem/relaxation.h"

namespace upgrain::dem {

// Collective; the same numbers on every rank.
RelaxationResult equilibrium_residual(const ParallelSimulation& sim);

// Collective.
RelaxationResult relax_to_equilibrium(ParallelSimulation& sim, const RelaxationOptions& options = {});

}  // namespace upgrain::dem
