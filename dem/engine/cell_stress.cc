#include "dem/engine/cell_stress.h"

#include "dem/engine/particle_sums.h"

namespace upgrain::dem {

Mat3 cell_stress_times_volume(const ParticleStore& p, int n_owned, const std::vector<ContactSample>& contacts,
                              Summation summation, MPI_Comm comm) {
  // Quantities 0-8: Weber's f (x) l, column-major as Eigen stores it; 9-14: the kinetic
  // m u (x) u, upper triangle by rows.
  constexpr int kWeber = 9;
  ParticleSums sums(summation, kWeber + 6, n_owned);
  const bool deterministic = summation == Summation::deterministic;
  for (const ContactSample& c : contacts) {
    if (c.with_wall() || (deterministic && c.a >= n_owned)) continue;
    const Vec3 l = p.x[static_cast<std::size_t>(c.b)] - p.x[static_cast<std::size_t>(c.a)];
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) sums.add(3 * col + row, c.a, c.force_on_a[row] * l[col]);
  }
  for (int i = 0; i < n_owned; ++i) {
    const Vec3& u = p.v[static_cast<std::size_t>(i)];
    const double m = p.mass(static_cast<std::size_t>(i));
    for (int k = kWeber, a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b) sums.add(k++, i, m * u[a] * u[b]);
  }
  const std::vector<double> t = sums.totals(comm);
  Mat3 s;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) s(row, col) = t[static_cast<std::size_t>(3 * col + row)];
  for (int k = kWeber, a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b, ++k) {
      s(a, b) -= t[static_cast<std::size_t>(k)];
      if (b != a) s(b, a) -= t[static_cast<std::size_t>(k)];
    }
  return s;
}

}  // namespace upgrain::dem
