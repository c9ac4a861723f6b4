#include "dem/stress/grid_stress.h"

#include <cmath>
#include <numbers>

#include "dem/stress/rigid_body_inertia.h"

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

Vec3 RegularGrid::cell_centre(int cell) const {
  const int i = cell % n[0], j = (cell / n[0]) % n[1], k = cell / (n[0] * n[1]);
  const Vec3 h = (hi - lo).cwiseQuotient(Vec3(n[0], n[1], n[2]));
  return lo + h.cwiseProduct(Vec3(i + 0.5, j + 0.5, k + 0.5));
}

GridStress grid_stress(const ParticleStore& p, const std::vector<ContactSample>& contacts,
                       const RegularGrid& grid, const GrainDynamics& dynamics) {
  const int cells = grid.num_cells();
  GridStress g;
  g.cell_volume = grid.cell_volume();
  for (auto& s : g.sigma) s.assign(cells, Mat3::Zero());
  g.particles.assign(cells, 0);
  g.internal_contacts.assign(cells, 0);
  g.external_contacts.assign(cells, 0);
  g.wall_contacts.assign(cells, 0);
  g.solid_fraction.assign(cells, 0.0);
  std::vector<Mat3>& weber = g.sigma[static_cast<int>(StressFormula::weber)];
  std::vector<Mat3>& drescher = g.sigma[static_cast<int>(StressFormula::drescher)];
  std::vector<Mat3>& bagi = g.sigma[static_cast<int>(StressFormula::bagi)];
  std::vector<Mat3>& de_saxce = g.sigma[static_cast<int>(StressFormula::de_saxce)];

  std::vector<int> cell(p.size());
  std::vector<Vec3> centre(cells);
  for (int c = 0; c < cells; ++c) centre[c] = grid.cell_centre(c);
  for (std::size_t i = 0; i < p.size(); ++i) {
    cell[i] = grid.cell_of(p.x[i]);
    if (cell[i] < 0) continue;
    ++g.particles[cell[i]];
    g.solid_fraction[cell[i]] += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius[i], 3);
  }
  // An external contact seen from the inside particle q, which receives force f at point.
  // De Saxce's absolute positions are taken from the cell centre: the formula is
  // translation invariant (its body term balances the contact forces), and this keeps the
  // sums free of cancellation far from the origin. Drescher's is not invariant and keeps
  // the scene's origin, as published.
  auto external = [&](int c, int q, const Vec3& point, const Vec3& f) {
    drescher[c] += f * point.transpose();
    bagi[c] += f * (point - p.x[q]).transpose();
    de_saxce[c] += f * (point - centre[c]).transpose();
  };
  for (const ContactSample& s : contacts) {
    const int ca = cell[s.a];
    if (s.with_wall()) {
      if (ca >= 0) {
        external(ca, s.a, s.point, s.force_on_a);
        ++g.wall_contacts[ca];
      }
      continue;
    }
    const int cb = cell[s.b];
    if (ca >= 0 && ca == cb) {
      const Mat3 t = s.force_on_a * (p.x[s.b] - p.x[s.a]).transpose();
      weber[ca] += t;
      bagi[ca] += t;
      ++g.internal_contacts[ca];
      continue;
    }
    if (ca >= 0) {
      external(ca, s.a, s.point, s.force_on_a);
      ++g.external_contacts[ca];
    }
    if (cb >= 0) {
      external(cb, s.b, s.point, -s.force_on_a);
      ++g.external_contacts[cb];
    }
  }

  // Per grain: the rotational inertial moment D (rigid_body_inertia.h), and De Saxce's body
  // term integral rho (g - a) (x) x dV = m (g - a^p) (x) x^p - D, where m (a^p - g) is the
  // grain's total contact force (force index first).
  std::vector<Mat3> inertial(cells, Mat3::Zero());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int c = cell[i];
    if (c < 0) continue;
    de_saxce[c] -= p.force[i] * (p.x[i] - centre[c]).transpose();
    if (!dynamics.rotation) continue;
    // Spheres: J = I 1, so w x (J w) = 0 and w_dot = T / I.
    const Mat3 inertia = Mat3::Identity() / p.inv_inertia[i];
    const Vec3 omega_dot = angular_acceleration(inertia, p.omega[i], p.torque[i]);
    inertial[c] += rigid_body_inertial_moment(second_moment_from_inertia(inertia), p.omega[i], omega_dot);
  }

  const double inv_v = 1.0 / g.cell_volume;
  for (int c = 0; c < cells; ++c) {
    de_saxce[c] -= inertial[c];
    g.sigma[static_cast<int>(StressFormula::nicot)][c] = weber[c] - inertial[c];
    g.sigma[static_cast<int>(StressFormula::modified_nicot)][c] = bagi[c] - inertial[c];
    // (7): integral rho y (x) a over a rigid grain is the same D (rigid_body_inertia.h), so
    // for rigid grains (6) and (7) coincide term by term.
    g.sigma[static_cast<int>(StressFormula::modified_de_saxce)][c] = bagi[c] - inertial[c];
    for (auto& s : g.sigma) s[c] *= inv_v;
    g.solid_fraction[c] *= inv_v;
  }
  return g;
}

}  // namespace upgrain::dem
