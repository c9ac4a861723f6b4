#pragma once
// Coarse-grained continuum fields at any points (docs/coarse-graining.md), after Goldhirsch
// (2010, Granular Matter 12:239) and Weinhart, Thornton, Luding & Bokhove (2012, Granular
// Matter 14:289): each grain smoothed by a kernel phi of width w, each contact along its
// branches by the kernel's line integral psi, so that the fields satisfy the balance of
// momentum exactly. Convention: sigma_ij = sum f_i l_j psi (force index first), compression
// negative, as the grid stress (docs/stress.md).
//
//   density            rho = sum m phi_i,  volume fraction nu = sum V_i phi_i
//   momentum           p = sum m v_i phi_i,  velocity V = p / rho (0 where rho = 0)
//   kinetic stress     sigma_k = -sum m (v_i - V)(v_i - V) phi_i
//   contact stress     sigma_c = sum over branches f (x) l psi(r; x_from, l)
//   wall force density b = sum over wall contacts f phi(r - c)
//   displacement       U = sum m u_i phi_i / rho,  grad U (quotient rule; F = (1 - grad U)^-1)
//   momentum balance   d(rho V)/dt + div(rho V V) - div sigma - rho g - b = residual
// with d(rho V)/dt = sum m a_i phi_i - sum m v_i (v_i . grad phi_i) from the grains'
// accelerations (the exact time derivative of p at the instant of the state), and
// div sigma_c = sum over branches f (phi(r - x_from) - phi(r - x_to)) (the kernel's gradient
// integrated along the branch), in which the contact points' terms of a pair's two branches
// cancel and a wall contact's is -b. residual_by_differences() takes d(rho V)/dt from two states
// instead.
#include <span>
#include <vector>

#include "upscale/cg/grain_state.h"
#include "upscale/cg/kernel_kind.h"

namespace upgrain::upscale::cg {

// One entry per point.
struct CoarseGrainedFields {
  std::vector<double> density, volume_fraction;
  std::vector<Vec3> momentum, velocity;
  std::vector<Mat3> kinetic_stress, contact_stress, stress;
  std::vector<Vec3> wall_force_density;
  std::vector<Vec3> displacement;           // zero without a reference state
  std::vector<Mat3> displacement_gradient;  // dU_i / dx_j
  // d(rho V)/dt from the accelerations, and the rest of the balance:
  // net_force_density = div sigma + rho g + b - div(rho V V), so that residual =
  // momentum_rate - net_force_density.
  std::vector<Vec3> momentum_rate, net_force_density, residual;

  [[nodiscard]] std::size_t size() const { return density.size(); }
  void resize(std::size_t n);
};

// The fields at `points` from the state (or the part of it near the points: part_near).
template <Kernel K>
CoarseGrainedFields coarse_grain(const GrainState& s, std::span<const Vec3> points, const K& kernel);
CoarseGrainedFields coarse_grain(const GrainState& s, std::span<const Vec3> points,
                                 const KernelChoice& kernel);

// The residual of the balance with d(rho V)/dt taken from two evaluations at the same points
// `interval` apart (trapezoidal: (p_later - p_earlier) / interval - (G_earlier + G_later) / 2
// with G the net force density), second order in the interval.
std::vector<Vec3> residual_by_differences(const CoarseGrainedFields& earlier,
                                          const CoarseGrainedFields& later, double interval);

}  // namespace upgrain::upscale::cg
