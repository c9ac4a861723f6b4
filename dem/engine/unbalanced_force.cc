#include "dem/engine/unbalanced_force.h"

namespace upgrain::dem {

double unbalanced_force_ratio(std::span<const Vec3> forces, std::span<const ContactSample> contacts) {
  double resultant = 0.0;
  for (const Vec3& f : forces) resultant += f.norm();
  double contact = 0.0;
  long count = 0;
  for (const ContactSample& c : contacts) {
    if (c.with_wall() || static_cast<std::size_t>(c.a) >= forces.size()) continue;
    contact += c.force_on_a.norm();
    ++count;
  }
  if (forces.empty() || count == 0 || contact == 0.0) return 0.0;
  return (resultant / static_cast<double>(forces.size())) / (contact / static_cast<double>(count));
}

}  // namespace upgrain::dem
