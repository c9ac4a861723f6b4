// The Insertion section: grains poured in during the run (docs/insertion.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto insertion(Member m) {
  return at(&SceneInput::scene, &dem::SceneConfig::insertion, m);
}

}  // namespace

Section insertion_section() {
  return {"Insertion",
          {integer("count", insertion(&dem::InsertionSpec::count), 0, 1e9, "-",
                   "Grains poured in during the run from the inlet box (docs/insertion.md), with the scene's "
                   "gradation and shapes; 0: no insertion."),
           real("rate", insertion(&dem::InsertionSpec::rate), 0.0, 1e12, "grains/s",
                "Grains inserted per second (give this or 'mass rate')."),
           real("mass rate", insertion(&dem::InsertionSpec::mass_rate), 0.0, 1e9, "kg/s",
                "Mass inserted per second (give this or 'rate')."),
           real("start time", insertion(&dem::InsertionSpec::start_time), 0.0, 1e6, "s",
                "Time of the first batch."),
           real("interval", insertion(&dem::InsertionSpec::interval), 1e-12, 1e6, "s",
                "Time between two batches; each brings the grains due by the rate."),
           vector3("inlet min", insertion(&dem::InsertionSpec::inlet_lo), -1e4, 1e4, "m",
                   "Lower corner of the inlet box, inside the container, where new grains are placed."),
           vector3("inlet max", insertion(&dem::InsertionSpec::inlet_hi), -1e4, 1e4, "m",
                   "Upper corner of the inlet box."),
           vector3("velocity", insertion(&dem::InsertionSpec::velocity), -1e4, 1e4, "m/s",
                   "Initial velocity of every new grain.")},
          nullptr};
}

}  // namespace upgrain::coupling::input
