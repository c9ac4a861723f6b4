#pragma once
// The DEM cell's contact-stiffness tangent in the solver's terms (docs/femxdem.md): the
// engine's contacts (dem/engine/contact_stiffnesses.h) turned into the solver's frame by the
// rotation Q of F = Q R (coupling/femxdem/cell_increment.h), Kruyt and Rothenburg's
// (1/V) sum K_ik d_j d_l (dem/stress/contact_tangent.h), its minor symmetries imposed, in Mandel
// notation (fem/plasticity/mandel.h).
#include "dem/engine/simulation.h"
#include "dem/stress/contact_tangent.h"
#include "fem/plasticity/mandel.h"

namespace upgrain::coupling {

// D projected onto the symmetric strains and stresses, (D_ijkl + D_jikl + D_ijlk + D_jilk) / 4,
// as the 6 x 6 Mandel matrix (the sqrt2 on the shear rows and columns).
[[nodiscard]] fem::Mat6 mandel_tangent(const dem::FullTangent& d);

// The tangent of the engine's last recorded evaluation over its cell's volume, its contacts
// turned by `rotation` (one rank: MPI_COMM_SELF).
[[nodiscard]] fem::Mat6 contact_tangent(const dem::Simulation& sim, const dem::Mat3& rotation);

}  // namespace upgrain::coupling
