#include "dem/parallel/parallel_relaxation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "dem/parallel/exchange.h"

namespace upgrain::dem {

namespace {

// Global sums of per-particle terms, the same bits on any rank count: the bound of each
// quantity is the exact global maximum of its |terms|, then the fixed-point sums.
class OwnedSums {
 public:
  OwnedSums(int quantities, int n_owned) : terms_(static_cast<std::size_t>(quantities)) {
    for (auto& t : terms_) t.assign(static_cast<std::size_t>(n_owned), 0.0);
  }
  double& term(int q, int i) { return terms_[q][i]; }
  std::vector<double> sums(MPI_Comm comm) const {
    std::vector<double> bound(terms_.size(), 0.0);
    for (std::size_t q = 0; q < terms_.size(); ++q)
      for (double t : terms_[q]) bound[q] = std::max(bound[q], std::abs(t));
    MPI_Allreduce(MPI_IN_PLACE, bound.data(), static_cast<int>(bound.size()), MPI_DOUBLE, MPI_MAX, comm);
    FixedPointSums s(bound);
    for (std::size_t q = 0; q < terms_.size(); ++q)
      for (double t : terms_[q]) s.add(static_cast<int>(q), t);
    return global_sums(s, comm);
  }

 private:
  std::vector<std::vector<double>> terms_;
};

}  // namespace

RelaxationResult equilibrium_residual(const ParallelSimulation& sim) {
  const ParticleStore& p = sim.local_particles();
  const int n = sim.owned();
  const Vec3 g = sim.gravity();
  // Without gravity the scale is the mean contact force magnitude, as the serial residual.
  double scale_force = 0.0;
  if (g.norm() == 0.0) {
    OwnedSums s(1, n);
    for (int i = 0; i < n; ++i) s.term(0, i) = p.force[i].norm();
    long count = n;
    MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_LONG, MPI_SUM, sim.comm());
    scale_force = std::max(s.sums(sim.comm())[0] / static_cast<double>(std::max(count, 1L)), 1e-300);
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

RelaxationResult relax_to_equilibrium(ParallelSimulation& sim, const RelaxationOptions& o) {
  const Vec3 g = sim.gravity();
  const bool rotation = sim.integrates_rotation();
  const MPI_Comm comm = sim.comm();
  double alpha = o.alpha_start;
  int since_uphill = 0;
  RelaxationResult r = equilibrium_residual(sim);
  for (long s = 0; s < o.max_steps; ++s) {
    if (r.max_force_residual < o.force_tolerance && r.max_torque_residual < o.force_tolerance) {
      r.converged = true;
      break;
    }
    sim.step();
    ++r.steps;
    ParticleStore& p = sim.local_particles_for_update();
    const int n = sim.owned();
    // Power of the resultant forces and torques, and the norms of the velocity mixing
    // (translation and rotation mixed separately: their units differ).
    enum { kPower, kV2, kF2, kW2, kT2 };
    OwnedSums terms(5, n);
    for (int i = 0; i < n; ++i) {
      const Vec3 f = p.force[i] + p.mass(static_cast<std::size_t>(i)) * g;
      terms.term(kPower, i) = f.dot(p.v[i]) + (rotation ? p.torque[i].dot(p.omega[i]) : 0.0);
      terms.term(kV2, i) = p.v[i].squaredNorm();
      terms.term(kF2, i) = f.squaredNorm();
      if (rotation) {
        terms.term(kW2, i) = p.omega[i].squaredNorm();
        terms.term(kT2, i) = p.torque[i].squaredNorm();
      }
    }
    const std::vector<double> sum = terms.sums(comm);
    OwnedSums removed(1, n);
    if (sum[kPower] > 0.0) {
      const double cv = sum[kF2] > 0.0 ? alpha * std::sqrt(sum[kV2] / sum[kF2]) : 0.0;
      const double cw = sum[kT2] > 0.0 ? alpha * std::sqrt(sum[kW2] / sum[kT2]) : 0.0;
      for (int i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        const Vec3 v = (1.0 - alpha) * p.v[i] + cv * (p.force[i] + p.mass(k) * g);
        double change = 0.5 * p.mass(k) * (p.v[i].squaredNorm() - v.squaredNorm());
        p.v[i] = v;
        if (rotation) {
          const Vec3 w = (1.0 - alpha) * p.omega[i] + cw * p.torque[i];
          change += p.rotational_energy(k) - p.rotational_energy(k, w);
          p.omega[i] = w;
        }
        removed.term(0, i) = change;
      }
      if (++since_uphill > o.delay_steps) alpha *= o.alpha_shrink;
    } else {
      // Uphill: stop every grain; its kinetic energy is booked as removed.
      for (int i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        double kinetic = 0.5 * p.mass(k) * p.v[i].squaredNorm();
        p.v[i].setZero();
        if (rotation) {
          kinetic += p.rotational_energy(k);
          p.omega[i].setZero();
        }
        removed.term(0, i) = kinetic;
      }
      alpha = o.alpha_start;
      since_uphill = 0;
    }
    const double joules = removed.sums(comm)[0];
    sim.account_removed_kinetic_energy(joules);
    r.kinetic_removed += joules;
    const RelaxationResult now = equilibrium_residual(sim);
    r.max_force_residual = now.max_force_residual;
    r.max_torque_residual = now.max_torque_residual;
  }
  if (!r.converged)
    r.converged = r.max_force_residual < o.force_tolerance && r.max_torque_residual < o.force_tolerance;
  return r;
}

}  // namespace upgrain::dem
