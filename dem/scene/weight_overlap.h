#pragma once
// How far a grain sinks into its support under its own weight by the scene's contact law: the
// overlap at which the law's normal force equals the weight of the scene's largest grain
// resting on the floor, as a fraction of its radius. DEM keeps static overlaps small (about
// 1 % of a radius and below, a common guideline; O'Sullivan, Particulate Discrete Element
// Modelling, 2011); much more means the grains are too soft to carry a bed, whatever the time
// step: the runaway-overlap guard (dem/engine/guards.h) tells the two causes apart with it.
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

// DEM practice's bound on a static overlap, as a fraction of the radius.
inline constexpr double kStaticOverlapBound = 0.01;

}  // namespace upgrain::dem
