#pragma once
// A complete, validated description of a deposition scene, as plain data. The driver
// (coupling/) fills it from a parameter file; tests fill it directly.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dem/boundary/container.h"
#include "dem/contact/contact_solver_settings.h"
#include "dem/contact/law/law_parameter.h"  // NamedValue
#include "dem/core/cell_motion.h"
#include "dem/core/effect_set.h"
#include "dem/core/material.h"
#include "dem/core/particle_store.h"
#include "dem/core/types.h"
#include "dem/scene/grain_shape.h"

namespace upgrain::dem {

// One point of a gradation curve: the mass fraction of grains with radius <= radius.
struct GradationPoint {
  double radius;            // m
  double fraction_passing;  // 0..1, non-decreasing, last point 1
};

struct ParticleSpec {
  long count = 2000;
  // Empty gradation: monodisperse spheres of `radius`.
  double radius = 1.5e-3;
  std::vector<GradationPoint> gradation;
  // Empty: spheres. Otherwise the mix of shapes; the radius above is each grain's major
  // semi-axis a, and orientations are uniformly random.
  std::vector<GrainShape> shapes;
  Material material;
  // An initial packing (docs/input.md, "Starting from a packing"): when set, the run starts
  // from these grains instead of a fill; count, radius and shapes then describe them (radius
  // the smallest major semi-axis, shapes the most demanding of theirs, for the time step).
  std::shared_ptr<const ParticleStore> packing;

  // The largest and smallest major semi-axis a grain of the scene can have.
  [[nodiscard]] double largest_radius() const {
    if (packing) return packing->max_radius();
    return gradation.empty() ? radius : gradation.back().radius;
  }
  [[nodiscard]] double smallest_radius() const {
    if (packing) return packing->min_radius();
    return gradation.empty() ? radius : gradation.front().radius;
  }
};

enum class FillMethod { lattice, random };

struct FillSpec {
  FillMethod method = FillMethod::lattice;
  double bottom_gap = 0.01;      // m, floor to the lowest particle surface
  double lattice_spacing = 1.1;  // lattice pitch in max diameters (lattice fill)
  double position_jitter = 0.5;  // random offset as a fraction of the free gap (lattice)
  double solid_fraction = 0.3;   // target solid fraction of the random fill region
  Vec3 velocity = Vec3::Zero();  // initial velocity of every particle (m/s)
  double velocity_jitter = 0.0;  // uniform random component of each velocity (m/s)
  std::uint64_t seed = 12345;
};

// Grains poured in during the run from an inlet box at a rate (docs/insertion.md), as
// LIGGGHTS fix insert/rate/region and LAMMPS fix pour. They take the scene's gradation and
// shapes; count 0: no insertion.
struct InsertionSpec {
  long count = 0;                // grains to pour in all
  double rate = 0.0;             // grains per second (when mass_rate is 0)
  double mass_rate = 0.0;        // kg per second; > 0 replaces `rate`
  double start_time = 0.0;       // s
  double interval = 0.01;        // s between two batches
  Vec3 inlet_lo = Vec3::Zero();  // the inlet box (m)
  Vec3 inlet_hi = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();  // initial velocity of every grain (m/s)

  [[nodiscard]] bool enabled() const { return count > 0; }
};

struct TimeStepRule {
  double rayleigh_fraction = 0.2;  // dt <= rayleigh_fraction * T_Rayleigh
  double hertz_fraction = 0.1;     // dt <= hertz_fraction * t_Hertz(v_impact)
  double impact_speed = 0.0;       // m/s; 0 = estimate from the drop height and velocities
  bool allow_unsafe = false;       // explicit override of the refusal
};

struct SceneConfig {
  ParticleSpec particles;
  BoxContainer container;
  // How the periodic cell deforms (docs/periodic.md, "A cell that deforms"); fixed by default.
  CellMotion cell;
  FillSpec fill;
  InsertionSpec insertion;
  EffectSet effects;
  // The contact law (dem/contact/contact_laws.h) and the values of its own parameters; a
  // parameter not listed takes the law's default.
  std::string contact_law = "hertz-mindlin";
  std::vector<NamedValue> law_parameters;
  double friction = 0.5;       // particle-particle Coulomb coefficient
  double damping_ratio = 0.5;  // zeta (docs/contact-law.md, eqs. 21-22)
  double gravity = 9.81;       // m/s^2 along -z, when effects.gravity
  double time_step = 1e-6;     // s
  double end_time = 0.4;       // s
  double neighbor_skin = 0.2;  // Verlet skin in units of the largest diameter
  // Rolling resistance, when effects.rolling_resistance (docs/contact-law.md).
  double rolling_friction = 0.05;      // mu_r: plastic limit |M_r| <= mu_r R* F_n
  double rolling_damping_ratio = 0.3;  // eta_r: dashpot C_r = eta_r 2 sqrt(I_r k_r)
  TimeStepRule time_step_rule;
  // The ellipsoid contact solver's stopping rules (docs/ellipsoid-contact.md).
  ContactSolverSettings contact_solver;
};

}  // namespace upgrain::dem
