#include "upscale/strain/periodic_kinematics.h"

#include <string>

#include "dem/core/error.h"

namespace upgrain::upscale {

PeriodicKinematics periodic_kinematics(const dem::PeriodicCell& cell, const Mat3& l,
                                       std::span<const GlobalId> id, std::span<const Vec3> x,
                                       std::span<const Vec3> u, std::span<const ImageCount> image,
                                       std::span<const GlobalId> reference_id,
                                       std::span<const ImageCount> reference_image) {
  if (x.size() != id.size() || u.size() != id.size() || image.size() != id.size() ||
      reference_image.size() != reference_id.size())
    throw Error("periodic_kinematics: " + std::to_string(id.size()) + " ids, " + std::to_string(x.size()) +
                " positions, " + std::to_string(u.size()) + " velocities, " + std::to_string(image.size()) +
                " image counters; " + std::to_string(reference_id.size()) + " reference ids, " +
                std::to_string(reference_image.size()) + " reference counters");
  PeriodicKinematics k;
  k.x.resize(id.size());
  k.v.resize(id.size());
  std::size_t r = 0;
  for (std::size_t i = 0; i < id.size(); ++i) {
    while (r < reference_id.size() && reference_id[r] < id[i]) ++r;
    const ImageCount n0 = r < reference_id.size() && reference_id[r] == id[i] ? reference_image[r] : image[i];
    const ImageCount dn = {image[i][0] - n0[0], image[i][1] - n0[1], image[i][2] - n0[2]};
    k.x[i] = dem::unwrapped(cell, x[i], dn);
    k.v[i] = u[i] + l * k.x[i];
  }
  return k;
}

}  // namespace upgrain::upscale
