#pragma once
// A pair whose geometry is not closed form (dem/contact/geometry/pair_geometries.h): the force
// loop collects such pairs in batches, one per geometry, solves each batch before the force
// pass, and reads the results in the slots' order.
#include <cstddef>

#include "dem/contact/contact_kinematics.h"
#include "dem/core/contact_history.h"

namespace upgrain::dem {

// One pair of a batch, and its geometry.
struct ShapedPair {
  std::size_t i = 0, j = 0;
  ShapedContactMemory* memory = nullptr;
  bool touching = false;
  // When touching: the geometry part of its ContactKinematics, and the held Hertz radius.
  Vec3 normal = Vec3::Zero();
  double overlap = 0.0;
  Vec3 lever_i = Vec3::Zero(), lever_j = Vec3::Zero();
  double r_star = 0.0;

  // Its geometry into a contact's kinematics, and its Hertz radius.
  void kinematics(ContactKinematics& kin, double& radius) const {
    kin.normal = normal;
    kin.overlap = overlap;
    kin.lever_i = lever_i;
    kin.lever_j = lever_j;
    radius = r_star;
  }
};

}  // namespace upgrain::dem
