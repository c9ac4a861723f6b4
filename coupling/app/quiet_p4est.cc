#include "coupling/app/quiet_p4est.h"

#include <p4est_base.h>

namespace upgrain::coupling {

void quiet_p4est() {
  // The threshold of deal.II's MPI_InitFinalize (deal.II 9.4, source/base/mpi.cc).
  if (p4est_package_id < 0) p4est_init(nullptr, SC_LP_SILENT);
}

}  // namespace upgrain::coupling
