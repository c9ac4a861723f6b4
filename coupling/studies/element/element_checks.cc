#include "coupling/studies/element/element_checks.h"

#include <array>
#include <cmath>
#include <sstream>

#include "dem/core/error.h"

namespace upgrain::coupling {

void check_element_study(SceneInput& in, const std::string& where) {
  const std::string study = where + "--study element: ";
  const std::array<bool, 3>& periodic = in.scene.container.periodic;
  for (int d = 0; d < 3; ++d)
    if (!periodic[d])
      throw Error(study + "the element tests run on a fully periodic cell, and the axis " +
                  std::string(1, "xyz"[d]) +
                  " is not periodic: set Container/periodic axes = x, y, z (docs/element-tests.md)");
  if (in.scene.cell.any())
    throw Error(study +
                "the study moves the cell itself; leave Cell/mode x, y and z fixed (docs/element-tests.md)");
  if (in.scene.insertion.enabled())
    throw Error(study + "the element tests take the scene's fill; a pour (Insertion/count > 0) is not one");
  const ElementOptions& o = in.element;
  if (o.pressures.empty()) throw Error(study + "Element test/pressures: give at least one pressure");
  for (double p : o.pressures)
    if (!(p > 0.0)) {
      std::ostringstream m;
      m << study << "Element test/pressures: each must be > 0 (Pa), not " << p;
      throw Error(m.str());
    }
  // The triaxial path records 100 states, the hold's quarter at least one step each.
  const double dt = in.scene.time_step;
  if (o.hold_time < 20.0 * dt) {
    std::ostringstream m;
    m << study << "Element test/hold time = " << o.hold_time << " s is shorter than 20 time steps ("
      << 20.0 * dt << " s)";
    throw Error(m.str());
  }
  if (steps_of(-std::log1p(-o.final_axial_strain) / o.axial_strain_rate, dt) < 2 * kTriaxialRecords) {
    std::ostringstream m;
    m << study << "Element test/final axial strain / axial strain rate gives fewer than 200 time steps of "
      << dt << " s: the triaxial path records 100 states; lower Element test/axial strain rate";
    throw Error(m.str());
  }
  for (double i : o.shear_inertial_numbers)
    if (!(i > 0.0 && i <= 1.0)) {
      std::ostringstream m;
      m << study << "Element test/shear inertial numbers: each must be in (0, 1], not " << i
        << " (above 1 the flow is no longer dense, GDR MiDi 2004)";
      throw Error(m.str());
    }
}

}  // namespace upgrain::coupling
