#include "coupling/studies/femxdem/femxdem_checks.h"

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
}

}  // namespace upgrain::coupling
