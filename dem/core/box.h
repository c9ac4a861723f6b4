#pragma once
// An axis-aligned box (the domain of a decomposition, a compute grid).
#include "dem/core/types.h"

namespace upgrain::dem {

struct Box {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
};

}  // namespace upgrain::dem
