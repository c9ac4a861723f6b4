#pragma once
// One contact as the stress formulas need it: who touches whom, where, and with which
// force. Recorded by the force loop itself at the steps that ask for it, so the forces are
// exactly those that moved the particles (docs/contact-law.md).
#include "dem/core/types.h"

namespace upgrain::dem {

struct ContactSample {
  int a;            // local index of the first particle
  int b;            // local index of the second particle, or -(w + 1) for wall w
  Vec3 point;       // contact point: mid-overlap (particles) or on the plane (walls)
  Vec3 force_on_a;  // the second body receives -force_on_a

  [[nodiscard]] bool with_wall() const { return b < 0; }
  [[nodiscard]] int wall() const { return -b - 1; }
};

}  // namespace upgrain::dem
