// The Fill section: how the initial grains are placed in the container.
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto fill(Member m) {
  return at(&SceneInput::scene, &dem::SceneConfig::fill, m);
}

}  // namespace

Section fill_section() {
  return {"Fill",
          {choice("method", fill(&dem::FillSpec::method),
                  {{"lattice", dem::FillMethod::lattice}, {"random", dem::FillMethod::random}},
                  "Initial placement: a jittered cubic lattice, or random sequential addition."),
           real("bottom gap", fill(&dem::FillSpec::bottom_gap), 0.0, 1e4, "m",
                "Gap between the floor and the lowest grain surface at the start."),
           real("lattice spacing", fill(&dem::FillSpec::lattice_spacing), 1.0, 10.0, "largest diameters",
                "Lattice pitch."),
           real("position jitter", fill(&dem::FillSpec::position_jitter), 0.0, 1.0, "-",
                "Random offset of lattice sites, as a fraction of the free gap between neighbours."),
           real("solid fraction", fill(&dem::FillSpec::solid_fraction), 0.01, 0.6, "-",
                "Solid fraction of the random fill region."),
           vector3("initial velocity", fill(&dem::FillSpec::velocity), -1e4, 1e4, "m/s",
                   "Initial velocity of every grain."),
           real("velocity jitter", fill(&dem::FillSpec::velocity_jitter), 0.0, 1e4, "m/s",
                "Amplitude of a uniform random velocity added to each grain."),
           integer("seed", fill(&dem::FillSpec::seed), 0, 2147483647, "-",
                   "Seed of the random numbers (radii, jitter).")},
          nullptr};
}

}  // namespace upgrain::coupling::input
