#include "dem/contact/grain_poses.h"

#include <cmath>
#include <limits>

namespace upgrain::dem {

void GrainPoses::update(const ParticleStore& p) {
  const std::size_t n = p.size();
  const std::size_t had = posed_.size();
  posed_.resize(n);
  id_.resize(n);
  motion_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    PosedEllipsoid& e = posed_[i];
    const Vec3 x = p.x[i];
    const Mat3 r = p.orientation[i].toRotationMatrix();
    if (i < had && id_[i] == p.id[i] && e.semi_axes == p.semi_axes[i]) {
      // h(n) = |D R^T n| with D = diag(a, b, c), so a turn from R to R' changes it by at most
      // |D (R' - R)^T n| <= a ||R' - R||_2 <= a ||R' - R||_F, and a move by |dc|. The margins
      // (1e-14 relative, and 1e-14 a) cover the rounding of R from the quaternion, of M from R
      // and of the differences, each a few epsilon.
      const double dr = std::sqrt((r - e.rot).squaredNorm());
      motion_[i] = std::sqrt((x - e.centre).squaredNorm()) * (1.0 + 1e-14) + e.major * (dr + 1e-14);
    } else {
      motion_[i] = std::numeric_limits<double>::infinity();
      id_[i] = p.id[i];
      e.semi_axes = p.semi_axes[i];
      e.major = e.semi_axes.maxCoeff();
      e.minor = e.semi_axes.minCoeff();
      e.min_radius = e.minor * e.minor / e.major;
    }
    e.centre = x;
    e.rot = r;
    e.shape = PosedEllipsoid::shape_of(r, e.semi_axes);
  }
}

}  // namespace upgrain::dem
