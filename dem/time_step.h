#pragma once
// Stability of the explicit integrator: the critical time steps of a Hertzian assembly.
#include <string>

#include "dem/scene/scene_config.h"

namespace upgrain::dem {

struct TimeStepEstimate {
  double rayleigh_time = 0.0;  // T_R of the smallest grain (s)
  double hertz_time = 0.0;     // shortest Hertz contact duration at impact_speed (s)
  double impact_speed = 0.0;   // speed used for hertz_time (m/s)
  double safe_step = 0.0;      // min(rayleigh_fraction T_R, hertz_fraction t_H)
  std::string limiting;        // "Rayleigh" or "Hertz"
};

// Rayleigh time T_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766) (Li et al. 2005, Powder
// Technol. 160:219; Thornton 2015) and the Hertz contact duration (Johnson eq. 11.24)
// for the smallest grain against an equal grain and against a wall.
TimeStepEstimate estimate_time_step(const SceneConfig& scene);

// The largest impact speed a scene produces by itself: the initial speed plus free fall
// from the top of the fill to the floor.
double expected_impact_speed(const SceneConfig& scene, double fill_top);

}  // namespace upgrain::dem
