// The Simulation section: the time step and its safety rule, the end of the run, the stop at rest, the
// neighbour skin.
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"
#include "coupling/run/scene_run.h"

namespace upgrain::coupling::input {

namespace {

template <class... Members>
auto scene(Members... m) {
  return at(&SceneInput::scene, m...);
}

}  // namespace

Section simulation_section() {
  return {"Simulation",
          {real("time step", scene(&dem::SceneConfig::time_step), 1e-12, 1.0, "s",
                "Fixed time step of the velocity Verlet integrator. Refused when above the safe step (see "
                "Rayleigh fraction, Hertz fraction) unless 'allow unsafe time step' is true."),
           real("end time", scene(&dem::SceneConfig::end_time), 0.0, 1e6, "s",
                "Simulated time at which the run ends."),
           real("maximum steps", at(&SceneInput::maximum_steps), 1.0, 1e18, "steps",
                "The most time steps (end time / time step) a scene may ask for; more is refused as a "
                "likely mistake in a unit (1e10 steps take a day at the fastest step rates measured). Raise"
                " it for a longer run."),
           real("stop at rest ratio", at(&SceneInput::control, &RunControl::rest_ratio), 0.0, 1.0, "-",
                "End the run early once the kinetic energy is below this fraction of the potential energy "
                "released at every time-series row for the rest window (checked after the first tenth of "
                "the run). 0 disables."),
           real("stop at rest window", at(&SceneInput::control, &RunControl::rest_window), 0.0, 1e6,
                "settling times",
                "How long the kinetic energy must stay below the rest ratio before the run stops, in "
                "settling times sqrt(d/g) (d the largest grain's diameter), so that a lull between bounces "
                "does not end a deposition. 0: the first row below the ratio."),
           real("Rayleigh fraction",
                scene(&dem::SceneConfig::time_step_rule, &dem::TimeStepRule::rayleigh_fraction), 1e-3, 1.0,
                "-", "Safe time step as a fraction of the Rayleigh time of the smallest grain."),
           real("Hertz fraction",
                scene(&dem::SceneConfig::time_step_rule, &dem::TimeStepRule::hertz_fraction), 1e-3, 1.0, "-",
                "Safe time step as a fraction of the shortest Hertz contact duration at the expected impact"
                " speed."),
           real("expected impact speed",
                scene(&dem::SceneConfig::time_step_rule, &dem::TimeStepRule::impact_speed), 0.0, 1e4, "m/s",
                "Highest relative impact speed for the Hertz time. 0 = estimate: initial speed plus free "
                "fall from the top of the fill."),
           boolean("allow unsafe time step",
                   scene(&dem::SceneConfig::time_step_rule, &dem::TimeStepRule::allow_unsafe),
                   "Run even when the time step exceeds the safe step (results may be wrong or unstable)."),
           real("neighbor skin", scene(&dem::SceneConfig::neighbor_skin), 0.01, 5.0, "largest diameters",
                "Verlet list skin; the list is rebuilt when a grain has moved more than half of it.")},
          nullptr};
}

}  // namespace upgrain::coupling::input
