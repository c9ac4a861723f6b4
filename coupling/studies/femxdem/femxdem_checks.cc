#include "coupling/studies/femxdem/femxdem_checks.h"

#include <string>

#include "coupling/studies/femxdem/cell_choice.h"
#include "dem/core/error.h"

namespace upgrain::coupling {

void check_femxdem_study(SceneInput& in, const std::string& where) {
  const std::string study = where + "--study femxdem: ";
  const FemxdemOptions& o = in.femxdem;
  if (in.scene.insertion.enabled())
    throw Error(study +
                "the DEM cells take the scene's grains as a fill; a pour (Insertion/count > 0) is not one");
  if (o.loading == FemxdemLoading::gravity_column && !(in.scene.effects.gravity && in.scene.gravity > 0.0))
    throw Error(study +
                "FEMxDEM/loading = gravity column: the column's weight needs Effects/gravity on and a "
                "positive Effects/gravity acceleration");
  if (o.residual_tolerance == 0.0 && o.correction_tolerance == 0.0)
    throw Error(study +
                "FEMxDEM/residual tolerance and correction tolerance are both 0: Newton could never end");
  if (o.rebalance_threshold > 0.0 && o.rebalance_threshold < 1.0)
    throw Error(
        study + "FEMxDEM/rebalance threshold = " + std::to_string(o.rebalance_threshold) +
        ": it is the busiest rank's grain-steps over the ranks' mean, at least 1 (0: never rebalance)");
  try {
    const CellSnapshotChoice chosen = parse_cell_snapshots(o.cell_snapshots);
    const long elements = static_cast<long>(o.cells_x) * o.cells_y;
    const int per_axis = o.quadrature_points > 0 ? o.quadrature_points : o.degree + 1;
    const auto points = static_cast<unsigned>(per_axis * per_axis);
    for (const auto& [element, point] : chosen.points)
      if (element >= elements || point >= points)
        throw Error("FEMxDEM/cell snapshots: " + std::to_string(element) + ":" + std::to_string(point) +
                    " is not a Gauss point of the mesh: elements 0 to " + std::to_string(elements - 1) +
                    ", points 0 to " + std::to_string(points - 1) + " in each");
  } catch (const Error& e) {
    throw Error(study + e.what());
  }
  if (o.degree == 1 && o.quadrature_points == 1)
    throw Error(study +
                "FEMxDEM/quadrature points = 1 with degree = 1: the specimen's sides are free, and one Gauss "
                "point leaves each element's hourglass modes without stiffness (a singular matrix); set "
                "quadrature points = 0 (degree + 1) or 2");
}

}  // namespace upgrain::coupling
