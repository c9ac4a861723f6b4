// The Lid section: a wall placed on the bed, driven or servo-controlled (docs/scenes.md, Lid).
#include "coupling/run/lid.h"
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto lid(Member m) {
  return at(&SceneInput::control, &RunControl::lid, m);
}

}  // namespace

Section lid_section() {
  return {
      "Lid",
      {choice("mode", lid(&LidControl::mode),
              {{"none", LidControl::Mode::none},
               {"velocity", LidControl::Mode::velocity},
               {"servo", LidControl::Mode::servo}},
              "A lid on the bed (docs/scenes.md, Lid): a horizontal wall placed at 'place time' just "
              "above the highest grain, then driven down at 'speed' (velocity) or servo-controlled to "
              "hold 'target stresses' (servo; docs/calibration.md). A run with a lid does not stop at "
              "rest. none: no lid."),
       real("place time", lid(&LidControl::place_time), 0.0, 1e6, "s",
            "Simulated time at which the lid is placed; before Simulation/end time."),
       real("gap", lid(&LidControl::gap), 0.0, 1e4, "m",
            "Distance between the highest grain's top (its bounding sphere's) and the lid when it is "
            "placed."),
       real("friction", lid(&LidControl::friction), 0.0, 10.0, "-",
            "Coulomb coefficient particle-lid (0 when Effects/wall friction is off)."),
       real("speed", lid(&LidControl::speed), -1e3, 1e3, "m/s",
            "Speed of the lid downwards, into the bed (mode velocity); negative lifts it."),
       numbers("target stresses", lid(&LidControl::target_stresses), "Pa",
               "Normal stresses on the lid (its force over the container's footprint) the servo holds in "
               "turn, comma-separated, each for 'step duration' after the placement, the last to the end "
               "(mode servo)."),
       real("step duration", lid(&LidControl::step_duration), 0.0, 1e6, "s",
            "Simulated time each target stress is held (mode servo); > 0 with more than one target."),
       real("gain factor", lid(&LidControl::gain_factor), 1e-6, 1.0, "-",
            "alpha of the servo's gain G = alpha A / (K dt), K a bound of the lid's contact stiffness: "
            "the error shrinks by (1 - alpha) per update on a linear spring; <= 1 for a stable servo "
            "(docs/calibration.md)."),
       real("max speed", lid(&LidControl::max_speed), 1e-9, 1e3, "m/s",
            "Largest speed of the servo lid, also its speed of approach before it touches the bed."),
       integer("update interval", lid(&LidControl::update_every), 1, 1000000, "steps",
               "Steps between servo updates; the lid keeps its velocity in between, and the gain takes the"
               " interval as its dt.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
