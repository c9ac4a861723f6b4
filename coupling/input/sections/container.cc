// The Container section: the box, its walls' friction and the collapse scenes (docs/scenes.md).
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto box(Member m) {
  return at(&SceneInput::scene, &dem::SceneConfig::container, m);
}

// The Coulomb coefficient of wall k (floor, x min, x max, y min, y max).
auto wall_friction(int k) {
  return [k](SceneInput& in) -> double& { return in.scene.container.friction[k]; };
}

// Whether axis d is periodic.
input::Flag periodic(int d) {
  return [d](SceneInput& in) -> bool& { return in.scene.container.periodic[d]; };
}

}  // namespace

Section container_section() {
  return {
      "Container",
      {real("length x", box(&dem::BoxContainer::lx), 1e-6, 1e4, "m",
            "Inner length of the box along x (walls at x = 0 and x = length x)."),
       real("length y", box(&dem::BoxContainer::ly), 1e-6, 1e4, "m", "Inner length of the box along y."),
       real("height", box(&dem::BoxContainer::height), 1e-6, 1e4, "m",
            "Nominal wall height (for output; the walls are unbounded planes)."),
       real("floor friction", wall_friction(0), 0.0, 10.0, "-", "Coulomb coefficient particle-floor."),
       real("wall x min friction", wall_friction(1), 0.0, 10.0, "-",
            "Coulomb coefficient at the wall x = 0."),
       real("wall x max friction", wall_friction(2), 0.0, 10.0, "-",
            "Coulomb coefficient at the wall x = length x."),
       real("wall y min friction", wall_friction(3), 0.0, 10.0, "-",
            "Coulomb coefficient at the wall y = 0."),
       real("wall y max friction", wall_friction(4), 0.0, 10.0, "-",
            "Coulomb coefficient at the wall y = length y."),
       real("gate x", box(&dem::BoxContainer::gate_x), 0.0, 1e4, "m",
            "Constrained collapse (paper): a gate wall at x = gate x holds the grains in [0, gate x] "
            "during deposition and is removed at 'gate open time', so the bed collapses into the rest "
            "of the box. 0 = no gate."),
       real("gate open time", box(&dem::BoxContainer::gate_open_time), 0.0, 1e6, "s",
            "Simulated time at which the gate is removed (with 'gate x' > 0)."),
       choice("collapse", at(&SceneInput::collapse),
              {{"none", std::string("none")},
               {"constrained", std::string("constrained")},
               {"unconstrained", std::string("unconstrained")}},
              "Collapse scene (docs/scenes.md). constrained: the gate at 'gate x' is removed at 'gate "
              "open time'. unconstrained: all four side walls are removed at 'side walls open time' and "
              "the bed spreads on the (unbounded) floor; needs 'Study/compare with continuum = false'. "
              "none: a plain box (a 'gate x' > 0 still selects the constrained collapse)."),
       real("side walls open time", box(&dem::BoxContainer::side_walls_open_time), 0.0, 1e6, "s",
            "Simulated time at which all side walls are removed (with 'collapse = unconstrained')."),
       flags("periodic axes", {{"x", periodic(0)}, {"y", periodic(1)}, {"z", periodic(2)}},
             "Axes along which the box is a periodic cell (docs/periodic.md): x over [0, length x], y over "
             "[0, length y], z over [0, height]. A periodic axis has no walls on its two faces; a grain "
             "leaving through one comes back through the other, and contacts across it are found with the "
             "nearest image. Each must be longer than twice the interaction range (two largest diameters "
             "and twice the skin). Empty: every axis walled. 'x, y' over the floor: a bed without side "
             "walls.")},
      nullptr};
}

}  // namespace upgrain::coupling::input
