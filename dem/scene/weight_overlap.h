#pragma once
// How far grains sink into each other by the scene's contact law, for each load that presses
// them: a grain's weight on the floor, an impact, and the mean stress an assembly carries. DEM
// keeps static overlaps small (about 1 % of a radius and below, a common guideline; O'Sullivan,
// Particulate Discrete Element Modelling, 2011); much more means the grains are too soft for
// the load, whatever the time step: the runaway-overlap guard (dem/engine/guards.h) tells the
// causes apart with these figures.
#include "dem/scene/scene_config.h"

namespace upgrain::dem {

// For Hertz: delta / R = (3 W / (4 E* sqrt(R)))^(2/3) / R (Johnson, Contact Mechanics, 1985,
// eq. 4.23); for Hooke: W / (k_n R). Solved on the law's own force, so any law of the table
// (dem/contact/contact_laws.h) gets its figure. 0 without gravity.
double weight_overlap_ratio(const SceneConfig& scene);

// How far a grain moving at `speed` against the floor sinks into it by the scene's contact law:
// the overlap at which the law's elastic energy equals the grain's kinetic energy m v^2 / 2
// (R* = R, m* = m), as a fraction of the radius; the scene's largest grain. For Hertz it does
// not depend on the size, (5 pi rho v^2 / (4 E*))^(2/5) (Johnson, Contact Mechanics, 1985,
// eq. 11.23 with m = 4/3 pi rho R^3), and an impact between equal grains reaches 0.87 of it.
// Beyond the runaway-overlap limit, the grains are too soft for the scene's impacts whatever
// the time step.
double impact_overlap_ratio(const SceneConfig& scene, double speed);

// The load of a fully periodic cell (the engine follows it while its cell deforms).
struct AssemblyLoad {
  double pressure = 0.0;        // -tr(sigma) / 3 (Pa), compression positive; 0: not known
  double coordination = 0.0;    // Z: 2 touching pairs per grain
  double solid_fraction = 0.0;  // phi: the grains' volume over the cell's
};

// The mean overlap in an assembly of the scene's grains under the mean stress p, as a fraction
// of the median radius r: the mean normal contact force of equal spheres, f = 4 pi r^2 p / (Z
// phi), from the Love-Weber stress p = (1/3V) sum_c f |l| with |l| = 2r, N_c = Z N / 2 and
// V = N 4/3 pi r^3 / phi, pressed by the law between two such grains (R* = r/2, m* = m/2). For
// Hertz it is (3 sqrt(2) pi p / (Z phi E*))^(2/3) whatever r: the overlaps of a stressed
// assembly fall as E^(-2/3) (Agnolin and Roux 2007, Phys. Rev. E 76, 061302, call
// kappa = (E / ((1 - nu^2) p))^(2/3) = (2 E* / p)^(2/3) its stiffness number). Force chains carry several
// times the mean force. 0 when the load is not known.
double stress_overlap_ratio(const SceneConfig& scene, const AssemblyLoad& load);

// DEM practice's bound on a static overlap, as a fraction of the radius.
inline constexpr double kStaticOverlapBound = 0.01;

}  // namespace upgrain::dem
