#pragma once
// Stability of the explicit integrator: the critical time steps of a Hertzian assembly.
#include <string>

#include "dem/scene/scene_config.h"

namespace upgrain::dem {

struct TimeStepEstimate {
  double rayleigh_time = 0.0;  // T_R of the smallest grain (s); 0 when the law has no such limit
  double contact_time = 0.0;   // the law's shortest contact duration (s)
  double hertz_time = 0.0;     // Hertz-Mindlin: the contact time, at impact_speed (s); else 0
  double impact_speed = 0.0;   // speed used for a Hertz contact time (m/s)
  double safe_step = 0.0;      // the law's rule, e.g. min(rayleigh_fraction T_R, hertz_fraction t_H)
  std::string limiting;        // "Rayleigh", "Hertz" or "Hooke"
};

// The time-step rule of the scene's contact law (its time_limit, dem/contact/law/): for
// Hertz-Mindlin the Rayleigh time T_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766) (Li et al.
// 2005, Powder Technol. 160:219; Thornton 2015) and the Hertz contact duration (Johnson eq.
// 11.24) of the smallest grain against an equal grain and against a wall; for the linear
// spring-dashpot pi sqrt(m*/k_n).
TimeStepEstimate estimate_time_step(const SceneConfig& scene);

// The largest impact speed a scene produces by itself: the initial speed plus free fall
// from the top of the fill (or of a pour's inlet, with its velocity) to the floor.
double expected_impact_speed(const SceneConfig& scene, double fill_top);

}  // namespace upgrain::dem
