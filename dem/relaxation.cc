#include "dem/relaxation.h"

#include <algorithm>
#include <cmath>

namespace upgrain::dem {

RelaxationResult equilibrium_residual(const Simulation& sim) {
  const ParticleStore& p = sim.particles();
  const Vec3 g = sim.gravity();
  // Without gravity the scale is the mean contact force magnitude.
  double scale_force = 0.0;
  if (g.norm() == 0.0) {
    for (std::size_t i = 0; i < p.size(); ++i) scale_force += p.force[i].norm();
    scale_force = std::max(scale_force / std::max<std::size_t>(p.size(), 1), 1e-300);
  }
  RelaxationResult r;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double w = g.norm() > 0.0 ? p.mass(i) * g.norm() : scale_force;
    r.max_force_residual = std::max(r.max_force_residual, (p.force[i] + p.mass(i) * g).norm() / w);
    if (sim.integrates_rotation())
      r.max_torque_residual = std::max(r.max_torque_residual, p.torque[i].norm() / (w * p.radius[i]));
  }
  return r;
}

RelaxationResult relax_to_equilibrium(Simulation& sim, const RelaxationOptions& o) {
  ParticleStore& p = sim.particles();
  const Vec3 g = sim.gravity();
  const bool rotation = sim.integrates_rotation();
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
    // Power of the resultant forces and torques, and the norms for the velocity mixing
    // (translation and rotation mixed separately: their units differ).
    double power = 0.0, v2 = 0.0, f2 = 0.0, w2 = 0.0, t2 = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3 f = p.force[i] + p.mass(i) * g;
      power += f.dot(p.v[i]);
      v2 += p.v[i].squaredNorm();
      f2 += f.squaredNorm();
      if (rotation) {
        power += p.torque[i].dot(p.omega[i]);
        w2 += p.omega[i].squaredNorm();
        t2 += p.torque[i].squaredNorm();
      }
    }
    if (power > 0.0) {
      const double cv = f2 > 0.0 ? alpha * std::sqrt(v2 / f2) : 0.0;
      const double cw = t2 > 0.0 ? alpha * std::sqrt(w2 / t2) : 0.0;
      // The mixing turns velocities towards the force; the small change of kinetic energy
      // it makes is booked too.
      double kinetic_change = 0.0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3 v = (1.0 - alpha) * p.v[i] + cv * (p.force[i] + p.mass(i) * g);
        kinetic_change += 0.5 * p.mass(i) * (p.v[i].squaredNorm() - v.squaredNorm());
        p.v[i] = v;
        if (rotation) {
          const Vec3 w = (1.0 - alpha) * p.omega[i] + cw * p.torque[i];
          kinetic_change += p.rotational_energy(i) - p.rotational_energy(i, w);
          p.omega[i] = w;
        }
      }
      sim.account_removed_kinetic_energy(kinetic_change);
      r.kinetic_removed += kinetic_change;
      if (++since_uphill > o.delay_steps) alpha *= o.alpha_shrink;
    } else {
      // Uphill: stop every grain; the kinetic energy is booked as removed.
      double kinetic = 0.0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        kinetic += 0.5 * p.mass(i) * p.v[i].squaredNorm();
        p.v[i].setZero();
        if (rotation) {
          kinetic += p.rotational_energy(i);
          p.omega[i].setZero();
        }
      }
      sim.account_removed_kinetic_energy(kinetic);
      r.kinetic_removed += kinetic;
      alpha = o.alpha_start;
      since_uphill = 0;
    }
    const RelaxationResult now = equilibrium_residual(sim);
    r.max_force_residual = now.max_force_residual;
    r.max_torque_residual = now.max_torque_residual;
  }
  if (!r.converged)
    r.converged = r.max_force_residual < o.force_tolerance && r.max_torque_residual < o.force_tolerance;
  return r;
}

}  // namespace upgrain::dem
