#pragma once
// Relaxation of a granular assembly to static equilibrium by FIRE, the fast inertial
// relaxation engine (Bitzek et al., Phys. Rev. Lett. 97, 170201, 2006): the dynamics of the
// run itself (same contact law, same time step) with velocities steered along the force and
// zeroed whenever the power turns negative. Used to bring beds to the rest state in which
// Yan and Regueiro's symmetry results hold (docs/stress.md, "Relaxed beds").
//
// Collective: its global sums (the power of the resultant forces and torques, the norms of
// the velocity mixing, the kinetic energy removed) follow the engine's summation
// (dem/engine/particle_sums.h) and its residuals are maxima over the ranks, so with
// deterministic summation the relaxed state is bitwise the same on any rank count.
#include <functional>

#include "dem/engine/simulation.h"

namespace upgrain::dem {

struct RelaxationResult;

// What `force_tolerance` bounds.
enum class EquilibriumMeasure {
  // Every grain's out-of-balance force |F + m g| over its weight m |g| (over the mean contact
  // force per grain without gravity), and its torque over m |g| r: the largest of either.
  grain_residual,
  // The unbalanced-force ratio (unbalanced_force.h): the mean |F + m g| over the mean contact
  // force, the criterion of Yade's quasi-static runs, which a cell without gravity can meet
  // with grains that merely rattle. Torques are not measured.
  unbalanced_force,
};

struct RelaxationOptions {
  // Stop when the measure below is under this.
  double force_tolerance = 1e-9;
  EquilibriumMeasure measure = EquilibriumMeasure::grain_residual;
  long max_steps = 200000;
  // FIRE constants (Bitzek et al. 2006, Table I, without the time-step adaptation: the DEM
  // step is already at its stability limit).
  double alpha_start = 0.1;
  double alpha_shrink = 0.99;
  int delay_steps = 5;
  // Called on every rank after each step with the result so far (a progress report; the
  // residuals are the same on every rank).
  std::function<void(const RelaxationResult&)> on_step;
};

struct RelaxationResult {
  long steps = 0;
  bool converged = false;
  double max_force_residual = 0.0;   // max |F + m g| / (m |g|) over grains
  double max_torque_residual = 0.0;  // max |T| / (m |g| r) over grains
  double unbalanced_force = 0.0;     // with EquilibriumMeasure::unbalanced_force
  double kinetic_removed = 0.0;      // J, booked in the run's energy balance
};

// Residuals of the current state (no step taken); the same on every rank.
RelaxationResult equilibrium_residual(const Simulation& sim);

RelaxationResult relax_to_equilibrium(Simulation& sim, const RelaxationOptions& options = {});

}  // namespace upgrain::dem
