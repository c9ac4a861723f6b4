#include "coupling/studies/femxdem/femxdem_checks.h"

#include <string>

#include "dem/core/error.h"

namespace upgrain::coupling {

void check_femxdem_study(SceneInput& in, const std::string& where) {
  const std::string study = where + "--study femxdem: ";
  const FemxdemOptions& o = in.femxdem;
  if (in.scene.insertion.enabled())
    throw Error(study +
                "the DEM cells take the scene's grains as a fill; a pour (Insertion/count > 0) is not one");
  if (o.residual_tolerance == 0.0 && o.correction_tolerance == 0.0)
    throw Error(study +
                "FEMxDEM/residual tolerance and correction tolerance are both 0: Newton could never end");
  if (o.rebalance_threshold > 0.0 && o.rebalance_threshold < 1.0)
    throw Error(
        study + "FEMxDEM/rebalance threshold = " + std::to_string(o.rebalance_threshold) +
        ": it is the busiest rank's grain-steps over the ranks' mean, at least 1 (0: never rebalance)");
  if (o.degree == 1 && o.quadrature_points == 1)
    throw Error(study +
                "FEMxDEM/quadrature points = 1 with degree = 1: the specimen's sides are free, and one Gauss "
                "point leaves each element's hourglass modes without stiffness (a singular matrix); set "
                "quadrature points = 0 (degree + 1) or 2");
}

}  // namespace upgrain::coupling
