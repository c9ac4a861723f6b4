#pragma once
// The strength of a granular sample sheared in a triaxial-like test (docs/calibration.md,
// "Friction angle"): the lateral stress sigma_3 held by servo walls, the axial stress sigma_1
// raised by a wall driven at a constant speed. From the stress-strain path:
//   the mobilised friction angle  sin phi_m = (sigma_1 - sigma_3) / (sigma_1 + sigma_3)
//     (the Mohr circle touching the Coulomb line through the origin, no cohesion);
//   its peak, and its critical-state value, the mean over the last part of the path (where the
//     sample shears at constant volume and stress), with the spread;
//   the dilatancy angle of triaxial compression from the plastic strain rates,
//     sin psi = -(d eps_v / d eps_1) / (2 - d eps_v / d eps_1)
//     (Bolton 1986, Geotechnique 36(1) 65-78; Schanz & Vermeer 1996, Geotechnique 46(1)
//     145-151, eq. 3; elastic strains neglected), eps_v compression positive, so that a
//     dilating sample (eps_v falling) has psi > 0;
//   Jaky's coefficient of earth pressure at rest K0 = 1 - sin phi (Jaky 1944);
//   the inertial number I = gamma_dot d sqrt(rho / p) (GDR MiDi 2004, Eur. Phys. J. E 14
//     341-365), below about 1e-3 a quasi-static test.
// Plain functions over plain numbers; compression and shortening positive, angles in degrees.
#include <vector>

namespace upgrain::dem {

struct TriaxialState {
  double axial_strain = 0.0;       // eps_1 from the start of shearing, shortening positive
  double volumetric_strain = 0.0;  // eps_v = 1 - V / V_0, compression positive
  double axial_stress = 0.0;       // sigma_1 (Pa)
  double lateral_stress = 0.0;     // sigma_3 (Pa)
};

// asin((s1 - s3) / (s1 + s3)) in degrees; throws upgrain::Error when s1 + s3 <= 0.
double mobilised_friction_angle(double sigma1, double sigma3);
// The triaxial dilatancy angle (degrees) of a volumetric strain rate ratio d eps_v / d eps_1.
double triaxial_dilatancy_angle(double volumetric_rate_ratio);
// The friction angle of triaxial compression with the Matsuoka-Nakai invariant I1 I2 / I3 of the
// principal compressions s1 >= s2 >= s3 > 0 (Matsuoka & Nakai 1974, Proc. JSCE 232, 59-70): a
// measure of the mobilised strength that counts the intermediate stress, so that states of
// other Lode angles (simple shear) compare with the triaxial test's. With s2 = s3 it is
// mobilised_friction_angle(s1, s3). Throws upgrain::Error unless s1 >= s2 >= s3 > 0.
double matsuoka_nakai_angle(double s1, double s2, double s3);
// Jaky's K0 = 1 - sin phi.
double jaky_k0(double friction_angle_deg);
// I = strain_rate d sqrt(density / pressure).
double inertial_number(double strain_rate, double diameter, double density, double pressure);

struct FrictionStrength {
  double peak_angle = 0.0;            // the largest running mean of the mobilised angle (degrees)
  double peak_strain = 0.0;           // eps_1 there
  double peak_rate_ratio = 0.0;       // d eps_v / d eps_1 around the peak
  double peak_dilatancy_angle = 0.0;  // psi from it (degrees)
  double critical_angle = 0.0;        // the mean mobilised angle over the critical part
  double critical_spread = 0.0;       // its standard deviation (degrees)
  double critical_rate_ratio = 0.0;   // d eps_v / d eps_1 over the critical part (about 0)
  double critical_from_strain = 0.0;  // the critical part: eps_1 at or above this
  int critical_states = 0;            // how many states it has
};

// The strength of a path (states in the order of growing axial strain, at least 3):
// the peak state, where the running mean of the mobilised angle over the states with
// |eps_1 - eps_k| <= peak_window is largest (that mean is the peak angle); the rate ratio there from the
// least-squares line of eps_v against eps_1 over the states with |eps_1 - eps_peak| <= peak_window (at least
// three: the nearest ones otherwise), and the critical part, the states with eps_1 >= (1 - critical_share)
// eps_max (0 < critical_share <= 1). Throws upgrain::Error for a path too short, or a strain that does not
// grow.
// The shares friction_strength() is called with by the calibration's and the element tests'
// triaxial paths: the critical state the last 30 % of the shearing; the peak's rate ratio over
// the states within a fifteenth of the final strain of the peak (+-0.01 at 0.15).
inline constexpr double kCriticalShare = 0.3;
inline constexpr double kPeakWindowShare = 1.0 / 15.0;

FrictionStrength friction_strength(const std::vector<TriaxialState>& path, double peak_window,
                                   double critical_share);

}  // namespace upgrain::dem
