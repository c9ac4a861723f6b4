#pragma once
// The element tests of `upgrain --study element` (docs/element-tests.md) on a fully periodic
// cell of grains, without gravity or walls (docs/periodic.md, "A cell that deforms"):
//   isotropic compression: the three axes servo to each pressure of a list in turn; at each,
//     the mean pressure reached, the solid fraction, the coordination number, and the bulk
//     modulus K = dp / d eps_v of a small isotropic strain step between two held cells;
//   drained triaxial compression from the last isotropic state: x and y servo to sigma_3 (the
//     last pressure), z shortened at a prescribed strain rate; the path of q/p, eps_v and the
//     solid fraction against eps_1, its peak and critical-state friction angles and dilatancy
//     (dem/analysis/triaxial.h), the secant modulus E50 and, with K, Poisson's ratio;
//   simple shear at a constant normal stress from the last isotropic state (Lees-Edwards, shear
//     along x across z, z servo to the last pressure): the steady friction coefficient and solid
//     fraction at each inertial number, and their fits mu(I), phi(I)
//     (dem/analysis/inertial_rheology.h).
// Plain C++ over the engine, collective over the communicator; with the deterministic summation
// the same bits on any rank count.
#include <mpi.h>

#include <string>
#include <vector>

#include "coupling/run/progress_clock.h"
#include "coupling/studies/element/element_options.h"
#include "dem/analysis/inertial_rheology.h"
#include "dem/analysis/triaxial.h"
#include "dem/engine/simulation.h"

namespace upgrain::coupling {

// One target of the isotropic compression.
struct IsotropicRecord {
  double target = 0.0;         // p* (Pa)
  dem::Vec3 pressure;          // -sigma_dd averaged over the last quarter of the hold (Pa)
  double mean_pressure = 0.0;  // their mean
  double solid_fraction = 0.0;
  long contacts = 0;          // touching pairs at the end of the hold
  double coordination = 0.0;  // 2 contacts / grains
  // The bulk modulus: the cell held still, then squeezed isotropically by the strain step, then
  // held again; p before and after (each the mean over the second half of its hold).
  double pressure_before = 0.0, pressure_after = 0.0;
  double volumetric_strain = 0.0;  // ln(V_before / V_after) of the step, compression positive
  double bulk_modulus = 0.0;       // (p_after - p_before) / volumetric_strain (Pa)
};

// One state of the triaxial path: strains from the start of shearing (compression positive),
// stresses averaged over the steps since the state before (compression positive).
struct ElementTriaxialRecord {
  double time = 0.0;  // since the start of shearing (s)
  dem::TriaxialState state;
  double mean_stress = 0.0;  // p = (sigma_1 + 2 sigma_3) / 3
  double deviator = 0.0;     // q = sigma_1 - sigma_3
  double solid_fraction = 0.0;
  double coordination = 0.0;
};

// One state of the simple shear at one inertial number, the stresses averaged over the steps
// since the state before (compression positive).
struct ShearPathRecord {
  double target_inertial_number = 0.0;
  double shear_strain = 0.0;          // gamma since the start of this inertial number's shear
  double shear_stress = 0.0;          // tau = (sigma_xz + sigma_zx) / 2 (Pa)
  double normal_stress = 0.0;         // P = -sigma_zz (Pa)
  double mean_stress = 0.0;           // p = -tr sigma / 3 (Pa)
  double mobilised_angle = 0.0;       // asin((s1 - s3) / (s1 + s3)) of the principal stresses (degrees)
  double intermediate_ratio = 0.0;    // b = (s2 - s3) / (s1 - s3)
  double matsuoka_nakai_angle = 0.0;  // triaxial compression's angle at the same I1 I2 / I3 (degrees)
  double solid_fraction = 0.0;
  double coordination = 0.0;
};

// The steady state at one inertial number: the means over the last half of its shear strain.
struct ShearSteadyState {
  double target_inertial_number = 0.0;
  double shear_rate = 0.0;  // gamma_dot = L_xz (1/s)
  long steps = 0;
  double inertial_number = 0.0;                   // gamma_dot d sqrt(rho / P) with the mean P
  double friction = 0.0;                          // mean tau / mean P
  double friction_spread = 0.0;                   // the standard deviation of tau / P over the states
  double normal_stress = 0.0, mean_stress = 0.0;  // Pa
  double mobilised_angle = 0.0;                   // the mean of the states' (degrees)
  double intermediate_ratio = 0.0;                // the mean of the states' b
  double matsuoka_nakai_angle = 0.0;              // the mean of the states' (degrees)
  double solid_fraction = 0.0, coordination = 0.0;
};

struct ElementResult {
  long particles = 0;
  double mean_diameter = 0.0;  // volume-equivalent (m)
  std::vector<IsotropicRecord> isotropic;
  std::vector<ElementTriaxialRecord> triaxial;  // the consolidated state, then the shearing
  double confining_pressure = 0.0;              // sigma_3 of the triaxial test (Pa)
  double inertial_number = 0.0;                 // of the shearing (GDR MiDi 2004)
  dem::FrictionStrength strength;               // NaN when it could not be taken
  std::string strength_error;
  double e50 = 0.0;            // q_peak / 2 over eps_1 there (Pa); NaN without a peak
  double poisson_ratio = 0.0;  // (3 K - E50) / (6 K), K of the last isotropic state
  std::vector<ShearPathRecord> shear_path;
  std::vector<ShearSteadyState> shear;  // one per shear inertial number
  dem::MuOfI mu_of_i;                   // the fits, with three or more inertial numbers
  dem::PhiOfI phi_of_i;
  std::string rheology_error;  // why there is no fit ("" when there is)
  double isotropic_seconds = 0.0, triaxial_seconds = 0.0, shear_seconds = 0.0;
};

// The tests on the grains `grains` (rank 0's; the other ranks may pass an empty store) in the
// periodic cell of `scene` (every axis periodic: the caller checked it), gravity off.
// Collective over `comm`; the result is the same on every rank.
ElementResult run_element_tests(const dem::SceneConfig& scene, dem::ParticleStore grains,
                                const ElementOptions& options, MPI_Comm comm,
                                const dem::EngineOptions& engine, const ProgressReport& on_progress = {});

}  // namespace upgrain::coupling
