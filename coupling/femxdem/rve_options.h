#pragma once
// The options of the DEM cell at a quadrature point of FEM x DEM (docs/femxdem.md, "The DEM cell
// at a quadrature point"): how the cell is prepared once, how each trial deforms and relaxes it,
// which tangent it returns. Each default written here once.
#include <cstdint>

namespace upgrain::coupling {

// The tangent d sigma / d eps a cell returns with its stress (docs/femxdem.md).
enum class RveTangent {
  contact_stiffness,  // (1/V) sum K_ik d_j d_l over the trial's contacts (Kruyt and Rothenburg 1998)
  perturbation,       // forward differences of extra trials, `perturbation` in each strain component
  elastic,            // the prepared cell's contact-stiffness tangent, kept fixed
};

// How a held cell is brought to equilibrium (held_cell.h, docs/femxdem.md).
enum class RveRelaxation {
  damped,  // the run's own dynamics, damped by the contact dashpots alone
  fire,    // FIRE's velocity mixing and stops (Bitzek et al. 2006) on the same dynamics
};

struct RveOptions {
  // Grains in the cell (the tests use 60).
  long grains = 200;
  // The isotropic stress the cell is prepared at (Pa, compression positive).
  double mean_stress = 1e5;
  // The steps of an increment Delta H: n = max(ceil(steps_per_unit_strain max|Delta H_ij|),
  // min_steps) (Guo and Zhao 2014: 1e5, at least 2): a strain of 1e-5 a step.
  double steps_per_unit_strain = 1e5;
  long min_steps = 2;
  // The held cell relaxes until the unbalanced-force ratio (mean |resultant| / mean |contact
  // force|, Yade's unbalancedForce; dem/engine/unbalanced_force.h) is at most this, or for at
  // most relaxation_step_cap steps (then the trial is not converged). Tight: after an increment of
  // 1e-4 the ratio is already below 1e-2 while the dashpots still carry a fifth of the stress
  // change (tests/femxdem/rve_cell_test.cc); at 1e-4 holding the cell moves it by under 1 %.
  double unbalanced_force_tolerance = 1e-4;
  long relaxation_step_cap = 20000;
  RveRelaxation relaxation = RveRelaxation::fire;
  RveTangent tangent = RveTangent::contact_stiffness;
  // The strain of each forward difference of the perturbation tangent (Mandel components): above
  // the relaxed cell's noise (at 1e-5 the differences of a 60-grain cell scatter by tens of per
  // cent, from 3e-5 on they agree within a few), Guo and Zhao's typical increment.
  double perturbation = 1e-4;
  // The fill's seed (distinct packings per point: rve_packings.h).
  std::uint64_t seed = 12345;
  // The preparation: the grains are placed at random at this solid fraction of the region their
  // centres may take in a cube (rve_preparation.cc), then a
  // servo on every axis (L_dd = gain (p_dd - p0) / p0, bounded by max_strain_rate; cell_motion.h)
  // squeezes them until every axis is within servo_tolerance of p0 and the cell is relaxed, or
  // for at most preparation_step_cap steps (then the preparation throws).
  double fill_solid_fraction = 0.3;
  double servo_gain = 10.0;       // 1/s
  double max_strain_rate = 10.0;  // 1/s
  double servo_tolerance = 0.02;  // of p0
  // The grains' friction coefficient while the servo squeezes them (negative: the scene's). The
  // lower, the denser the packing it jams in (0: the densest, as Thornton 2000, Geotechnique 50,
  // 43, prepares dense samples); the scene's coefficient is restored for the trials.
  double preparation_friction = -1.0;
  long preparation_step_cap = 2000000;

  friend bool operator==(const RveOptions&, const RveOptions&) = default;
};

}  // namespace upgrain::coupling
