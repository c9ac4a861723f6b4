// The Cell section: how a periodic cell deforms (docs/periodic.md, "A cell that deforms").
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "coupling/input/scene_input.h"
#include "coupling/input/scene_sections.h"
#include "dem/core/error.h"

namespace upgrain::coupling::input {

namespace {

dem::CellAxisControl& axis(SceneInput& in, int d) { return in.scene.cell.axis[static_cast<std::size_t>(d)]; }

// The entries of one axis: its mode, its prescribed rate and its servo's target.
void add_axis(std::vector<Entry>& entries, int d) {
  const std::string a(1, "xyz"[d]);
  entries.push_back(choice(
      "mode " + a, [d](SceneInput& in) -> dem::CellAxisMode& { return axis(in, d).mode; },
      {{"fixed", dem::CellAxisMode::fixed},
       {"rate", dem::CellAxisMode::rate},
       {"servo", dem::CellAxisMode::servo}},
      "How the cell's length along " + a +
          " moves (a periodic axis, Container/periodic axes): fixed; rate, at 'strain rate " + a + "' (L_" +
          a + a + ", h' = L h); servo, to 'target pressure " + a + "'."));
  entries.push_back(real(
      "strain rate " + a, [d](SceneInput& in) -> double& { return axis(in, d).rate; }, -1e4, 1e4, "1/s",
      "L_" + a + a + " with 'mode " + a + " = rate'; < 0 compresses."));
  entries.push_back(real(
      "target pressure " + a, [d](SceneInput& in) -> double& { return axis(in, d).target_pressure; }, 0.0,
      1e12, "Pa",
      "The servo's target of -sigma_" + a + a + " (compression positive) with 'mode " + a + " = servo'."));
}

std::vector<Entry> cell_entries() {
  std::vector<Entry> e;
  for (int d = 0; d < 3; ++d) add_axis(e, d);
  auto each_axis = [](double dem::CellAxisControl::*member) {
    // One value for the three axes' servos, kept in each.
    return [member](SceneInput& in) -> double& { return in.scene.cell.axis[0].*member; };
  };
  e.push_back(real("servo gain", each_axis(&dem::CellAxisControl::gain), 0.0, 1e6, "1/(Pa s)",
                   "The servo's L_dd = gain (p_dd - target), p = -sigma the cell's pressure (Love-Weber and "
                   "kinetic parts): a cell pressed harder than its target expands. Needed (> 0) with a servo "
                   "axis; a start: max strain rate / target pressure."));
  e.push_back(real("max strain rate", each_axis(&dem::CellAxisControl::max_rate), 0.0, 1e4, "1/s",
                   "The bound on the servo's |L_dd| (> 0 with a servo axis)."));
  // Simple shear: one off-diagonal component of L, the cell's images sliding (Lees-Edwards).
  std::vector<std::pair<std::string, std::array<int, 2>>> components{{"none", {-1, -1}}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (a != b) components.push_back({std::string(1, "xyz"[a]) + "xyz" [b], { a, b }});
  e.push_back(choice(
      "shear component",
      at(&SceneInput::scene, &dem::SceneConfig::cell, &dem::CellMotion::shear,
         &dem::CellShearControl::component),
      components,
      "Simple shear: the component L_sg = d v_s / d x_g of L set by 'shear rate' (xz: the grains' mean "
      "flow along x grows with z), both axes periodic; the images across the faces of g slide along s "
      "(Lees-Edwards, docs/periodic.md, \"Shear\"). The axis s keeps one block (Parallel/blocks)."));
  e.push_back(real(
      "shear rate",
      at(&SceneInput::scene, &dem::SceneConfig::cell, &dem::CellMotion::shear, &dem::CellShearControl::rate),
      -1e4, 1e4, "1/s", "L_sg with a 'shear component'."));
  e.push_back(real("max growth",
                   at(&SceneInput::scene, &dem::SceneConfig::cell, &dem::CellMotion::max_growth), 1.0, 1024.0,
                   "-",
                   "How many times its first length the cell may grow along an axis: its position grid is "
                   "sized for it (docs/periodic.md, \"Exact images\"); the run stops past it."));
  return e;
}

// The servo's gain and bound, given once, in every axis; a servo needs both.
void check_cell(SceneInput& in, const std::string& where) {
  dem::CellMotion& m = in.scene.cell;
  for (int d = 1; d < 3; ++d) {
    m.axis[d].gain = m.axis[0].gain;
    m.axis[d].max_rate = m.axis[0].max_rate;
  }
  if (m.shear.any() && m.shear.rate == 0.0)
    throw Error(where + "Cell/shear component = " + std::string(1, "xyz"[m.shear.shear()]) +
                "xyz"[m.shear.gradient()] + " needs a Cell/shear rate other than 0 (1/s)");
  if (!m.shear.any() && m.shear.rate != 0.0)
    throw Error(where + "Cell/shear rate is given without a Cell/shear component (xz, say)");
  for (int d = 0; d < 3; ++d) {
    if (m.axis[d].mode != dem::CellAxisMode::servo) continue;
    const std::string a(1, "xyz"[d]);
    if (!(m.axis[d].gain > 0.0))
      throw Error(where + "Cell/mode " + a +
                  " = servo needs Cell/servo gain > 0 (1/(Pa s)): without it the servo cannot move the cell "
                  "towards 'target pressure " +
                  a + "'");
    if (!(m.axis[d].max_rate > 0.0))
      throw Error(where + "Cell/mode " + a + " = servo needs Cell/max strain rate > 0 (1/s)");
  }
}

}  // namespace

Section cell_section() { return {"Cell", cell_entries(), check_cell}; }

}  // namespace upgrain::coupling::input
