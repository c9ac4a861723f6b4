#pragma once
// Objective rates of the Cauchy stress at a sequence of outputs (docs/strain.md, eq. (9)):
//   Jaumann       sigma_dot - W sigma + sigma W,               W = skew L
//   Green-Naghdi  sigma_dot - Omega sigma + sigma Omega,       Omega = R_dot R^T
//   Truesdell     sigma_dot - L sigma - sigma L^T + tr(L) sigma
//   Oldroyd       sigma_dot - L sigma - sigma L^T
// Each is the time derivative seen by an observer that turns (Jaumann, Green-Naghdi) or
// deforms (Truesdell, Oldroyd) with the material, so it vanishes for a stress that is only
// carried along: Q sigma0 Q^T under a rigid spin (all four), R sigma0 R^T (Green-Naghdi),
// F S F^T / J (Truesdell), F S F^T (Oldroyd), with S and sigma0 fixed.
//
// The material derivative sigma_dot (and R_dot) is not available from the outputs: it is
// taken by second-order finite differences over the output times, eq. (10). On outputs
// t_{k-1} < t_k < t_{k+1} with h1 = t_k - t_{k-1}, h2 = t_{k+1} - t_k (any spacing):
//   interior (central):  f'_k ~ [-h2^2 f_{k-1} + (h2^2 - h1^2) f_k + h1^2 f_{k+1}] / (h1 h2 (h1 + h2))
//   first output (one-sided, 3 points) and last output (mirrored), also second order;
// error O(h^2) everywhere: leading term +h1 h2 f'''/6 interior and -h_e (h1 + h2) f'''/6 at
// an end, h_e the interval at that end (-h^2 f'''/3 for even spacing, twice the central
// error); exact for quadratics in t. With two outputs only, the two-point difference
// (first order) is used; with one, no rate.
#include <span>
#include <string>
#include <vector>

#include "dem/core/types.h"

namespace upgrain::upscale {

using dem::Mat3;

// Pointwise kernels: sigma_dot, sigma and the kinematic tensor at one instant.
inline Mat3 jaumann_rate(const Mat3& sigma_dot, const Mat3& sigma, const Mat3& w) {
  return sigma_dot - w * sigma + sigma * w;
}
inline Mat3 green_naghdi_rate(const Mat3& sigma_dot, const Mat3& sigma, const Mat3& omega) {
  return sigma_dot - omega * sigma + sigma * omega;
}
inline Mat3 truesdell_rate(const Mat3& sigma_dot, const Mat3& sigma, const Mat3& l) {
  return sigma_dot - l * sigma - sigma * l.transpose() + l.trace() * sigma;
}
inline Mat3 oldroyd_rate(const Mat3& sigma_dot, const Mat3& sigma, const Mat3& l) {
  return sigma_dot - l * sigma - sigma * l.transpose();
}

// d/dt of a tensor series at every output by the formulas above. Requires strictly
// increasing finite times and at least 2 outputs (the caller checks; see objective_rates).
std::vector<Mat3> time_derivative(std::span<const double> times, std::span<const Mat3> values);

struct ObjectiveRates {
  bool valid = false;
  std::string reason;
  // One entry per output (empty when not valid).
  std::vector<Mat3> sigma_dot;
  std::vector<Mat3> jaumann;
  std::vector<Mat3> green_naghdi;  // empty when no rotation series was given
  std::vector<Mat3> truesdell;
  std::vector<Mat3> oldroyd;
};

// The four rates of one grid cell at each output from its stress series, the velocity
// gradient L at the same outputs and, for Green-Naghdi, the rotation R of the polar
// decomposition of the total F at the same outputs (pass an empty span to skip it;
// Omega = skew(R_dot R^T), R_dot by the same differences, the skew part removing the
// O(h^2) symmetric part that differencing leaves). Invalid when the lengths differ, fewer
// than 2 outputs are given, the times are not strictly increasing, or a value is not finite.
ObjectiveRates objective_rates(std::span<const double> times, std::span<const Mat3> sigma,
                               std::span<const Mat3> velocity_gradient, std::span<const Mat3> rotation);

}  // namespace upgrain::upscale
