#pragma once
// Energy accounting of a run (docs/integrator.md): kinetic, potential and elastic
// energies of the current state plus the energy dissipated so far by normal damping and
// by Coulomb slip. Their sum is conserved by the physics; its drift is the balance error.

#include <cmath>
#include <limits>

namespace upgrain::dem {

struct EnergyBalance {
  double kinetic_translational = 0.0;
  double kinetic_rotational = 0.0;
  double potential = 0.0;  // m g z, relative to the floor
  double elastic_normal = 0.0;
  double elastic_tangential = 0.0;
  double dissipated_damping = 0.0;   // cumulative since the start
  double dissipated_friction = 0.0;  // cumulative since the start
  // Cumulative energy created (> 0) in the tangential springs by their stiffness following
  // the overlap (contact/contact_response.h); it enters the balance with a minus sign.
  double tangential_stiffness_change = 0.0;
  // Rolling resistance (contact/rolling_resistance.h): energy of the rolling springs,
  // cumulative plastic and viscous dissipation, cumulative energy created by k_r following
  // the overlap (minus sign, as tangential_stiffness_change). Zero without the effect.
  double elastic_rolling = 0.0;
  double dissipated_rolling = 0.0;
  double rolling_stiffness_change = 0.0;
  // Kinetic energy taken out by a relaxation to equilibrium (dem/engine/relaxation.h).
  double removed_by_relaxation = 0.0;
  // Cumulative work of moving walls on the grains (sum of F . v_wall dt): energy put in, with a
  // minus sign in the balance.
  double work_by_walls = 0.0;
  // Cumulative work of a deforming periodic cell on the grains (V sigma : L dt, docs/periodic.md,
  // "A cell that deforms"): energy put in, with a minus sign in the balance. The kinetic energy
  // of such a cell is the peculiar one, of v - L x.
  double work_by_cell = 0.0;

  [[nodiscard]] double kinetic() const { return kinetic_translational + kinetic_rotational; }
  [[nodiscard]] double total() const {
    return kinetic() + potential + elastic_normal + elastic_tangential + dissipated_damping +
           dissipated_friction + removed_by_relaxation - tangential_stiffness_change + elastic_rolling +
           dissipated_rolling - rolling_stiffness_change - work_by_walls - work_by_cell;
  }
};

// The relative drift of the total energy since e0, over the energy put into play (initial
// kinetic and elastic energy, the potential energy released and the work of moving walls):
// the balance error of docs/integrator.md.
inline double balance_error(const EnergyBalance& e0, const EnergyBalance& e) {
  const double reference = e0.kinetic() + std::abs(e0.potential - e.potential) + e0.elastic_normal +
                           e0.elastic_tangential + std::abs(e.work_by_walls - e0.work_by_walls) +
                           std::abs(e.work_by_cell - e0.work_by_cell);
  // Not tracked (NaN channels): unknown, not zero.
  if (!std::isfinite(reference) || !std::isfinite(e.total()) || !std::isfinite(e0.total()))
    return std::numeric_limits<double>::quiet_NaN();
  return reference > 0.0 ? (e.total() - e0.total()) / reference : 0.0;
}

// Kinetic energy over the potential energy released since e0 (the at-rest criterion);
// infinite while nothing has been released.
inline double kinetic_to_released(const EnergyBalance& e0, const EnergyBalance& e) {
  const double released = e0.potential - e.potential;
  return released > 0.0 ? e.kinetic() / released : std::numeric_limits<double>::infinity();
}

}  // namespace upgrain::dem
