#pragma once
// What a normal-force part of a contact law gives for one overlap: the elastic force, the
// tangent stiffness (for the dashpot and the rolling spring) and the stiffness of the
// tangential spring that goes with it (Mindlin for Hertz, a constant for a linear law).
// The elastic energy is asked for separately, only by loops that track energy.

namespace upgrain::dem {

struct NormalResponse {
  double force;                 // elastic part of the normal force (N), >= 0
  double stiffness;             // dF/d(delta) (N/m)
  double tangential_stiffness;  // k_t of the incremental tangential spring (N/m)
};

}  // namespace upgrain::dem
