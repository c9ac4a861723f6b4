#include "dem/stress/grid_stress.h"

#include <cmath>

namespace upgrain::dem {

int RegularGrid::cell_of(const Vec3& x) const {
  int c[3];
  for (int d = 0; d < 3; ++d) {
    const double s = (x[d] - lo[d]) / (hi[d] - lo[d]) * n[d];
    if (!(s >= 0.0) || s >= n[d]) return -1;
    c[d] = static_cast<int>(s);
  }
  return (c[2] * n[1] + c[1]) * n[0] + c[0];
}

GridStress static_grid_stress(const ParticleStore& p, const std::vector<ContactSample>& contacts,
                              const RegularGrid& grid) {
  const int cells = grid.num_cells();
  GridStress g;
  g.cell_volume = grid.cell_volume();
  g.weber.assign(cells, Mat3::Zero());
  g.drescher.assign(cells, Mat3::Zero());
  g.bagi.assign(cells, Mat3::Zero());
  g.particles.assign(cells, 0);
  g.internal_contacts.assign(cells, 0);
  g.external_contacts.assign(cells, 0);

  std::vector<int> cell(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    cell[i] = grid.cell_of(p.x[i]);
    if (cell[i] >= 0) ++g.particles[cell[i]];
  }
  // An external contact seen from the inside particle q, which receives force f.
  auto external = [&](int c, int q, const Vec3& point, const Vec3& f) {
    g.drescher[c] += f * point.transpose();
    g.bagi[c] += f * (point - p.x[q]).transpose();
    ++g.external_contacts[c];
  };
  for (const ContactSample& s : contacts) {
    const int ca = cell[s.a];
    if (s.with_wall()) {
      if (ca >= 0) external(ca, s.a, s.point, s.force_on_a);
      continue;
    }
    const int cb = cell[s.b];
    if (ca >= 0 && ca == cb) {
      const Mat3 t = s.force_on_a * (p.x[s.b] - p.x[s.a]).transpose();
      g.weber[ca] += t;
      g.bagi[ca] += t;
      ++g.internal_contacts[ca];
      continue;
    }
    if (ca >= 0) external(ca, s.a, s.point, s.force_on_a);
    if (cb >= 0) external(cb, s.b, s.point, -s.force_on_a);
  }
  const double inv_v = 1.0 / g.cell_volume;
  for (int c = 0; c < cells; ++c) {
    g.weber[c] *= inv_v;
    g.drescher[c] *= inv_v;
    g.bagi[c] *= inv_v;
  }
  return g;
}

}  // namespace upgrain::dem
