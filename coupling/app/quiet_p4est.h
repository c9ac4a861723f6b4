#pragma once
// p4est (the distributed meshes of fem/ and upscale/) logs every mesh operation to stdout
// unless its package is registered with a log threshold; deal.II's
// Utilities::MPI::MPI_InitFinalize registers it silent, and the driver, which starts MPI
// itself, does the same once after MPI_Init.
namespace upgrain::coupling {

void quiet_p4est();

}  // namespace upgrain::coupling
