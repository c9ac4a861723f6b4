#pragma once
// Relative asymmetry index of a stress tensor (Yan and Regueiro eq. 20; docs/stress.md):
// RAI = ||skew(s)|| / ||sym(s) with its diagonal set to 0||, with the induced 2-norm
// (largest singular value). This reading reproduces Yan and Regueiro's printed values (e.g.
// Weber, 68 spheres: 15.1 %).
#include "dem/core/types.h"

namespace upgrain::dem {

// As a fraction (0.151, not 15.1). Zero when the off-diagonal symmetric part vanishes
// and the tensor is symmetric; infinity when only the skew part is non-zero.
double relative_asymmetry_index(const Mat3& s);

}  // namespace upgrain::dem
