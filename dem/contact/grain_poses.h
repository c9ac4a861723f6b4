#pragma once
// Every grain of a store posed once per force evaluation (rotation and shape matrices, for
// the contact geometry of ellipsoid scenes), with a bound on how far each grain moved since its
// previous pose. The bound lets a pair proven apart stay proven without a new evaluation while
// the two grains have not moved by more than its gap (docs/ellipsoid-contact.md, "Separation
// budget").
#include <vector>

#include "dem/contact/ellipsoid_geometry.h"
#include "dem/core/particle_store.h"

namespace upgrain::dem {

class GrainPoses {
 public:
  // Poses grains 0 .. p.size() - 1. A grain that was at the same index with the same id and
  // semi-axes at the previous update keeps its constants and gets a finite motion bound; any
  // other (new, reordered, migrated, a ghost now holding another grain) gets an infinite one.
  void update(const ParticleStore& p);

  [[nodiscard]] const PosedEllipsoid& operator[](std::size_t i) const { return posed_[i]; }
  [[nodiscard]] std::size_t size() const { return posed_.size(); }
  // Upper bound on the change of the support function h_i(n) = sqrt(n^T M_i n) + n.c_i of grain
  // i, for every unit n, between its previous pose and this one (m): |dc| + a ||dR||_F, with a
  // margin for the rounding of the poses.
  [[nodiscard]] double motion(std::size_t i) const { return motion_[i]; }

 private:
  std::vector<PosedEllipsoid> posed_;
  std::vector<GlobalId> id_;
  std::vector<double> motion_;
};

}  // namespace upgrain::dem
