#pragma once
// Sampling grain radii from a gradation curve (mass fraction passing vs radius), the way
// soil mechanics states a grain-size distribution (ASTM D6913).
#include <random>
#include <vector>

#include "dem/scene/scene_config.h"

namespace upgrain::dem {

// Throws upgrain::Error when the curve is not a valid distribution function.
void validate_gradation(const std::vector<GradationPoint>& curve);

// Draws `count` radii whose mass distribution follows the curve: the mass fraction
// passing is linear in radius between the points. A radius drawn from the mass
// distribution is accepted with probability (r_min / r)^3, which turns mass weights into
// number weights (the number density is the mass density divided by r^3).
std::vector<double> sample_radii(const std::vector<GradationPoint>& curve, long count, std::mt19937_64& rng);

// The mean acceptance probability of that draw, E[(r_min / r)^3] over the mass distribution:
// sample_radii takes about count / acceptance draws, which a curve spanning decades of radius
// makes astronomically many (the scene's validation refuses those, coupling/input/scene_limits.h).
double sampling_acceptance(const std::vector<GradationPoint>& curve);

}  // namespace upgrain::dem
