#pragma once
// The oedometric (constrained, laterally fixed) compression of a bed read as a linear elastic
// material (docs/calibration.md, "Oedometric test"): from the states of a stress path, the
// constrained modulus M = d sigma_v / d eps_v of each step, the coefficient of earth pressure at
// rest K0 = sigma_h / sigma_v of each state, and the Young's modulus and Poisson's ratio of the
// isotropic elastic material with that M and K0:
//   K0 = nu / (1 - nu)  =>  nu = K0 / (1 + K0),
//   M = E (1 - nu) / ((1 + nu)(1 - 2 nu))  =>  E = M (1 + nu)(1 - 2 nu) / (1 - nu)
// (isotropic linear elasticity under uniaxial strain: M is the P-wave modulus).
// Plain functions over plain numbers; compression and shortening positive.
#include <vector>

namespace upgrain::dem {

struct OedometerState {
  double vertical_stress = 0.0;    // sigma_v (Pa), compression positive
  double horizontal_stress = 0.0;  // sigma_h (Pa), the mean of the two horizontal normal stresses
  double vertical_strain = 0.0;    // eps_v from the first state, shortening positive
};

struct OedometerStep {
  double stress = 0.0;   // sigma_v at the step's middle (the mean of its two states)
  double modulus = 0.0;  // M = delta sigma_v / delta eps_v (Pa), the secant of the step
  double k0 = 0.0;       // K0 at its end state
  double poisson = 0.0;  // nu from K0
  double youngs = 0.0;   // E from M and nu
};

double poisson_from_k0(double k0);
double youngs_from_constrained(double constrained_modulus, double poisson);
// K0 of an isotropic elastic material under lateral constraint, nu / (1 - nu).
inline double k0_from_poisson(double nu) { return nu / (1.0 - nu); }

// One step per pair of consecutive states (throws upgrain::Error when the strain does not grow).
std::vector<OedometerStep> oedometer_steps(const std::vector<OedometerState>& path);

// The equivalent elastic material at a stress level: M from the least-squares power law
// M = a sigma^b through the steps (granular media stiffen as a power of the stress: b = 1/3 for
// a Hertz lattice, about 1/2 for real sands), K0 from the least-squares line of K0 against
// ln sigma_v through the states; nu and E from those. One step: its M, the states' mean K0.
// Each fit is evaluated within its data's stress range: a stress below (above) it takes the fit
// at the lowest (highest) stress, where `modulus_stress` says.
struct ElasticEquivalent {
  double stress = 0.0;
  double modulus = 0.0;
  double modulus_stress = 0.0;  // the stress M was evaluated at
  double exponent = 0.0;        // b of the power law (0 with one step)
  double k0 = 0.0;
  double poisson = 0.0;
  double youngs = 0.0;
};
ElasticEquivalent elastic_equivalent(const std::vector<OedometerState>& path, double stress);

// The closed-form oedometric response of a column of n Hertz spheres of radius r stacked
// between two rigid walls (a simple-cubic frictionless lattice, laterally confined by walls
// that touch it): under the column force F each of the n - 1 sphere contacts closes by
// delta(F, r/2) and each of the two wall contacts by delta(F, r), delta(F, R*) =
// (3 F / (4 E* sqrt(R*)))^(2/3) (Johnson 1985, eq. 4.23). The vertical strain at the stress
// sigma = F / (2r)^2 over the column's height 2 n r; the horizontal stress stays 0 (the lattice
// has no lateral contact force), so K0 = 0. For n -> infinity, sigma = 2/3 E* eps^(3/2) and
// M = E*^(2/3) (3 sigma / 2)^(1/3).
double hertz_column_strain(double stress, double e_star, double radius, int spheres);

// The oedometric test by gravity (docs/calibration.md, "Oedometric test by gravity"): a bed
// of height H in a box with frictionless side walls, loaded by its own weight W raised by a
// factor. By equilibrium its mean vertical stress over the footprint A and the height
// H = 2 zc (zc its centre of mass) is W / (2 A), whatever its stiffness (the integral of
// sigma_zz over the bed is W zc). A column of uniform constrained modulus M settles by
// u(z) = gamma (H z - z^2 / 2) / M (gamma = W / (A H)): its mean strain is u(H) / H =
// sigma_v / M, and its centre of mass comes down by gamma H^2 / (3 M), 4/3 of the mean strain
// times zc. So the mean vertical strain of a settlement from zc0 to zc is
//     eps_v = 3/4 (zc0 - zc) / zc0,
// and M = d sigma_v / d eps_v of the states of a gravity path is the constrained modulus of the
// uniform column that settles as the bed does: for a bed whose stiffness grows with the stress,
// an average over its depth, the one a uniform continuum loaded by gravity needs.
double centroid_vertical_strain(double centroid0, double centroid);

// The centre of mass's height of a column of n Hertz spheres of radius r stacked on a rigid
// floor (a simple-cubic frictionless lattice) under the weight w of each sphere: the floor
// contact carries n w and closes by delta(n w, r), the contact above sphere k (from the
// floor, k = 0 .. n - 2) carries (n - 1 - k) w and closes by delta(., r / 2), with delta of
// hertz::overlap_for_force (Johnson 1985, eq. 4.23).
double hertz_column_centroid(double sphere_weight, double e_star, double radius, int spheres);

}  // namespace upgrain::dem
