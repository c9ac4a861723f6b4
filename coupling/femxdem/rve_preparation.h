#pragma once
// The DEM cell that every quadrature point of FEM x DEM starts from (docs/femxdem.md, "The DEM
// cell at a quadrature point"): made once, copied to every point. N grains of the scene's
// material, gradation and contact law are placed at random in a fully periodic cube, squeezed by
// a servo on every axis to the isotropic stress p0 (as the element study's isotropic state,
// docs/element-tests.md), then held still and relaxed (as Guo and Zhao 2014: one packing
// prepared isotropically, copied to every Gauss point).
#include <memory>

#include "coupling/femxdem/rve_options.h"
#include "dem/engine/engine_state.h"
#include "dem/engine/simulation.h"
#include "dem/scene/scene_config.h"
#include "fem/plasticity/mandel.h"

namespace upgrain::coupling {

struct RveTemplate {
  dem::SceneConfig scene;     // the cell's scene: a periodic cube, no gravity, no walls
  dem::EngineOptions engine;  // the options its engine was made with
  dem::EngineState state;     // the prepared cell, held still and relaxed
  dem::Mat3 reference_cell = dem::Mat3::Identity();  // its matrix h0: the reference of F = 1 + H
  fem::Vec6 stress = fem::Vec6::Zero();              // its stress (tension positive, Mandel)
  fem::Mat6 elastic_tangent = fem::Mat6::Zero();     // its contact-stiffness tangent
  long grains = 0;
  double grain_volume = 0.0;    // the grains' volume (m^3), the solid of the solid fraction
  double grain_mass = 0.0;      // the grains' mass (kg): over the reference cell's volume, the
                                // density the continuum's body force acts on
  long contacts = 0;            // touching pairs at the end
  long steps = 0;               // the preparation's steps (servo and relaxation)
  double unbalanced_force = 0;  // the ratio at the end
};

// The frame of the cell prepare_rve() makes with these options: its scene, engine options, grains
// and their volume, from the same fill held still, without the servo and the relaxation (a
// fill and one engine, milliseconds against the preparation's seconds). A cell loaded from its
// bytes needs no more (RveCell::load). The state, stress, tangents and counts are left empty.
[[nodiscard]] RveTemplate rve_frame(const dem::SceneConfig& scene, const RveOptions& o);

// Collective over nothing: the cell runs on MPI_COMM_SELF. Throws upgrain::Error when the servo
// or the relaxation does not reach its target within RveOptions::preparation_step_cap steps.
[[nodiscard]] RveTemplate prepare_rve(const dem::SceneConfig& scene, const RveOptions& o);

}  // namespace upgrain::coupling
