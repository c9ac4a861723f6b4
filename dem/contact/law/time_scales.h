#pragma once
// The scales of a scene a contact law's time-step rule reads: the lightest and smallest
// grains, the flattest grain surface, the impact speed, the material. Worked out once
// (dem/time_step.cc) for every law.
#include <string>

#include "dem/core/material.h"

namespace upgrain::dem {

struct SceneTimeScales {
  Material material;
  double r_min = 0.0;         // smallest grain size (sphere radius, ellipsoid major semi-axis a)
  double thinnest = 1.0;      // smallest c/a of the mix (1 for spheres)
  double flattest = 1.0;      // largest Gaussian radius factor (b/a)/(c/a) at a c pole (1 for spheres)
  double lightest = 0.0;      // mass of the lightest grain (kg)
  double impact_speed = 0.0;  // m/s, > 0
};

// What a law's rule gives: its limit on the time step and its name, with the time scales
// behind it for the report.
struct LawTimeLimit {
  double rayleigh_time = 0.0;  // 0 when the law has no elastic-wave limit
  double contact_time = 0.0;   // shortest contact duration of the law (s)
  double safe_step = 0.0;      // s
  std::string limiting;        // "Rayleigh", "Hertz", "Hooke", ...
};

}  // namespace upgrain::dem
