#include "coupling/femxdem/rve_tangent.h"

#include <array>
#include <utility>
#include <vector>

#include "dem/engine/contact_stiffnesses.h"

namespace upgrain::coupling {

fem::Mat6 mandel_tangent(const dem::FullTangent& d) {
  // Mandel's order (mandel.h): xx, yy, zz, xy, xz, yz.
  static constexpr std::array<std::pair<int, int>, 6> pairs{{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
  fem::Mat6 m;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const auto [i, j] = pairs[static_cast<std::size_t>(a)];
      const auto [k, l] = pairs[static_cast<std::size_t>(b)];
      const double sym = 0.25 * (d(3 * i + j, 3 * k + l) + d(3 * j + i, 3 * k + l) + d(3 * i + j, 3 * l + k) +
                                 d(3 * j + i, 3 * l + k));
      const double w = (a < 3 ? 1.0 : fem::mandel::sqrt2) * (b < 3 ? 1.0 : fem::mandel::sqrt2);
      m(a, b) = w * sym;
    }
  return m;
}

fem::Mat6 contact_tangent(const dem::Simulation& sim, const dem::Mat3& rotation) {
  std::vector<dem::ContactStiffness> contacts = dem::contact_stiffnesses(sim);
  for (dem::ContactStiffness& c : contacts) {
    c.branch = rotation * c.branch;
    c.normal = rotation * c.normal;
  }
  return mandel_tangent(dem::contact_stiffness_tangent(contacts, sim.cell_matrix().determinant()));
}

}  // namespace upgrain::coupling
