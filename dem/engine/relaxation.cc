#include "dem/engine/relaxation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "dem/engine/particle_sums.h"
#include "dem/engine/unbalanced_force.h"

namespace upgrain::dem {

RelaxationResult equilibrium_residual(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  const int n = sim.owned();
  const Vec3 g = sim.gravity();
  // Without gravity the scale is the mean contact force magnitude.
  double scale_force = 0.0;
  if (g.norm() == 0.0) {
    ParticleSums s(sim.summation(), 1, n);
    for (int i = 0; i < n; ++i) s.add(0, i, p.force[i].norm());
    scale_force =
        std::max(s.totals(sim.comm())[0] / static_cast<double>(std::max(sim.particle_count(), 1L)), 1e-300);
  }
  double local[2] = {0.0, 0.0};
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double w = g.norm() > 0.0 ? p.mass(k) * g.norm() : scale_force;
    local[0] = std::max(local[0], (p.force[i] + p.mass(k) * g).norm() / w);
    if (sim.integrates_rotation()) local[1] = std::max(local[1], p.torque[i].norm() / (w * p.radius[i]));
  }
  MPI_Allreduce(MPI_IN_PLACE, local, 2, MPI_DOUBLE, MPI_MAX, sim.comm());
  RelaxationResult r;
  r.max_force_residual = local[0];
  r.max_torque_residual = local[1];
  return r;
}

namespace {

// The residuals `measure` asks for; an unbalanced-force ratio not yet known (no contacts recorded
// at the last step) is infinite.
RelaxationResult measured(const Simulation& sim, EquilibriumMeasure measure) {
  if (measure == EquilibriumMeasure::grain_residual) return equilibrium_residual(sim);
  RelaxationResult r;
  r.unbalanced_force = sim.contacts_recorded() ? unbalanced_force_ratio(sim) : HUGE_VAL;
  return r;
}

bool in_equilibrium(const RelaxationResult& r, const RelaxationOptions& o) {
  if (o.measure == EquilibriumMeasure::unbalanced_force) return r.unbalanced_force <= o.force_tolerance;
  return r.max_force_residual < o.force_tolerance && r.max_torque_residual < o.force_tolerance;
}

}  // namespace

RelaxationResult relax_to_equilibrium(Simulation& sim, const RelaxationOptions& o) {
  // In the cell where the run stopped: a deforming one is held still meanwhile.
  sim.hold_cell(true);
  const Vec3 g = sim.gravity();
  const bool rotation = sim.integrates_rotation();
  double alpha = o.alpha_start;
  int since_uphill = 0;
  const bool by_ratio = o.measure == EquilibriumMeasure::unbalanced_force;
  RelaxationResult r = measured(sim, o.measure);
  for (long s = 0; s < o.max_steps; ++s) {
    if (in_equilibrium(r, o)) {
      r.converged = true;
      break;
    }
    if (by_ratio) sim.request_contacts();
    sim.step();
    ++r.steps;
    ParticleStore& p = sim.particles();
    const int n = sim.owned();
    // Power of the resultant forces and torques, and the norms of the velocity mixing
    // (translation and rotation mixed separately: their units differ).
    enum { kPower, kV2, kF2, kW2, kT2 };
    ParticleSums sums(sim.summation(), 5, n);
    for (int i = 0; i < n; ++i) {
      const Vec3 f = p.force[i] + p.mass(static_cast<std::size_t>(i)) * g;
      sums.add(kPower, i, f.dot(p.v[i]));
      sums.add(kV2, i, p.v[i].squaredNorm());
      sums.add(kF2, i, f.squaredNorm());
      if (rotation) {
        sums.add(kPower, i, p.torque[i].dot(p.omega[i]));
        sums.add(kW2, i, p.omega[i].squaredNorm());
        sums.add(kT2, i, p.torque[i].squaredNorm());
      }
    }
    const std::vector<double> sum = sums.totals(sim.comm());
    ParticleSums removed(sim.summation(), 1, n);
    if (sum[kPower] > 0.0) {
      const double cv = sum[kF2] > 0.0 ? alpha * std::sqrt(sum[kV2] / sum[kF2]) : 0.0;
      const double cw = sum[kT2] > 0.0 ? alpha * std::sqrt(sum[kW2] / sum[kT2]) : 0.0;
      // The mixing turns velocities towards the force; the small change of kinetic energy it
      // makes is booked too.
      for (int i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const Vec3 v = (1.0 - alpha) * p.v[i] + cv * (p.force[i] + p.mass(k) * g);
        removed.add(0, i, 0.5 * p.mass(k) * (p.v[i].squaredNorm() - v.squaredNorm()));
        p.v[i] = v;
        if (rotation) {
          const Vec3 w = (1.0 - alpha) * p.omega[i] + cw * p.torque[i];
          removed.add(0, i, p.rotational_energy(k) - p.rotational_energy(k, w));
          p.omega[i] = w;
        }
      }
      if (++since_uphill > o.delay_steps) alpha *= o.alpha_shrink;
    } else {
      // Uphill: stop every grain; its kinetic energy is booked as removed.
      for (int i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        removed.add(0, i, 0.5 * p.mass(k) * p.v[i].squaredNorm());
        p.v[i].setZero();
        if (rotation) {
          removed.add(0, i, p.rotational_energy(k));
          p.omega[i].setZero();
        }
      }
      alpha = o.alpha_start;
      since_uphill = 0;
    }
    const double joules = removed.totals(sim.comm())[0];
    sim.account_removed_kinetic_energy(joules);
    r.kinetic_removed += joules;
    const RelaxationResult now = measured(sim, o.measure);
    r.max_force_residual = now.max_force_residual;
    r.max_torque_residual = now.max_torque_residual;
    r.unbalanced_force = now.unbalanced_force;
    if (o.on_step) {
      RelaxationResult so_far = r;
      so_far.converged = in_equilibrium(r, o);
      o.on_step(so_far);
    }
  }
  if (!r.converged) r.converged = in_equilibrium(r, o);
  sim.hold_cell(false);
  return r;
}

}  // namespace upgrain::dem
