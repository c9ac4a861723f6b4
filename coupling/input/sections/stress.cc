// The Stress section: the average-stress formulas on a grid (docs/stress.md).
#include "coupling/input/formula_choices.h"
#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"

namespace upgrain::coupling::input {

namespace {

template <class Member>
auto grid(Member m) {
  return at(&SceneInput::output, &OutputOptions::grid_stress, m);
}

}  // namespace

Section stress_section() {
  return {"Stress",
          {subset("formulas", grid(&dem::io::GridStressOptions::formulas), stress_formula_choices(),
                  "Average-stress formulas written per grid cell (paper eqs. 1-7, docs/stress.md), "
                  "comma-separated. Empty: no grid stress."),
           integer3("grid cells", grid(&dem::io::GridStressOptions::cells), 1, 1000, "-",
                    "Cells of the stress grid along x, y, z."),
           text("box", at(&SceneInput::stress_box), "m",
                "Box of the stress grid as 'x0, y0, z0, x1, y1, z1', or 'auto': the container footprint "
                "from the floor to the top of the highest grain at each evaluation."),
           real("interval", grid(&dem::io::GridStressOptions::interval), 0.0, 1e6, "s",
                "Simulated time between grid-stress evaluations; 0 = with each snapshot. The final state is"
                " always evaluated.")},
          nullptr};
}

}  // namespace upgrain::coupling::input
