#include "upscale/cg/periodic_images.h"

#include <cmath>

namespace upgrain::upscale::cg {

std::vector<Vec3> image_shifts(const dem::PeriodicCell& cell, double reach) {
  int m[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a)
    if (cell.periodic[a]) m[a] = static_cast<int>(std::ceil(reach / cell.length(a)));
  const dem::ShearImages& le = cell.shear;
  if (le.any()) ++m[le.shear];
  std::vector<Vec3> shifts;
  for (int k = -m[2]; k <= m[2]; ++k)
    for (int j = -m[1]; j <= m[1]; ++j)
      for (int i = -m[0]; i <= m[0]; ++i) {
        if (i == 0 && j == 0 && k == 0) continue;
        const int n[3] = {i, j, k};
        Vec3 t = Vec3::Zero();
        for (int a = 0; a < 3; ++a) t[a] = n[a] * cell.length(a);
        if (le.any()) t[le.shear] += n[le.gradient] * le.offset;
        shifts.push_back(t);
      }
  return shifts;
}

GrainState with_periodic_images(const GrainState& s, double reach) {
  if (!s.cell.any()) return s;
  const dem::Box& box = s.cell.box;
  GrainState out = s;
  out.cell = dem::PeriodicCell{};
  for (const Vec3& t : image_shifts(s.cell, reach)) {
    for (std::size_t i = 0; i < s.grains(); ++i)
      if (point_near(s.x[i] + t, box, reach)) append_grain(out, s, i, &t);
    for (std::size_t k = 0; k < s.branches(); ++k)
      if (segment_near(s.branch_from[k] + t, s.branch_to[k] + t, box, reach)) append_branch(out, s, k, &t);
    for (std::size_t k = 0; k < s.wall_contacts(); ++k)
      if (point_near(s.wall_point[k] + t, box, reach)) append_wall_contact(out, s, k, &t);
  }
  return out;
}

}  // namespace upgrain::upscale::cg
