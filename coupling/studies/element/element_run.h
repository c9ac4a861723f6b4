#pragma once
// The element tests of `upgrain --study element` (docs/element-tests.md) on a fully periodic
// cell of grains, without gravity or walls (docs/periodic.md, "A cell that deforms"):
//   isotropic compression: the three axes servo to each pressure of a list in turn; at each,
//     the mean pressure reached, the solid fraction, the coordination number, and the bulk
//     modulus K = dp / d eps_v of a small isotropic strain step between two held cells;
//   drained triaxial compression from the last isotropic state: x and y servo to sigma_3 (the
//     last pressure), z shortened at a prescribed strain rate; the path of q/p, eps_v and the
//     solid fraction against eps_1, its peak and critical-state friction angles and dilatancy
//     (dem/analysis/triaxial.h), the secant modulus E50 and, with K, Poisson's ratio.
// Plain C++ over the engine, collective over the communicator; with the deterministic summation
// the same bits on any rank count.
#include <mpi.h>

#include <string>
#include <vector>

#include "coupling/run/progress_clock.h"
#include "coupling/studies/element/element_options.h"
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
  double isotropic_seconds = 0.0, triaxial_seconds = 0.0;
};

// Both tests on the grains `grains` (rank 0's; the other ranks may pass an empty store) in the
// periodic cell of `scene` (every axis periodic: the caller checked it), gravity off.
// Collective over `comm`; the result is the same on every rank.
ElementResult run_element_tests(const dem::SceneConfig& scene, dem::ParticleStore grains,
                                const ElementOptions& options, MPI_Comm comm,
                                const dem::EngineOptions& engine, const ProgressReport& on_progress = {});

}  // namespace upgrain::coupling
