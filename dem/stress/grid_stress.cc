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

StressSums& StressSums::operator+=(const StressSums& o) {
  weber += o.weber;
  drescher += o.drescher;
  bagi += o.bagi;
  de_saxce += o.de_saxce;
  inertial += o.inertial;
  particles += o.particles;
  internal_contacts += o.internal_contacts;
  external_contacts += o.external_contacts;
  wall_contacts += o.wall_contacts;
  solid_volume += o.solid_volume;
  return *this;
}

void add_grain_count(StressSums& s, double volume) {
  ++s.particles;
  s.solid_volume += volume;
}

void add_grain_terms(StressSums& s, const ParticleStore& p, std::size_t i, const Vec3& centre,
                     const GrainDynamics& dynamics) {
  s.de_saxce -= p.force[i] * (p.x[i] - centre).transpose();
  if (!dynamics.rotation) return;
  // World-frame inertia Q J_body Q^T (spheres: I 1, so w x (J w) = 0 and w_dot = T / I);
  // w_dot from the full Euler equations (rigid_body_inertia.h).
  const Mat3 inertia = p.inertia_world(i);
  const Vec3 omega_dot = angular_acceleration(inertia, p.omega[i], p.torque[i]);
  s.inertial += rigid_body_inertial_moment(second_moment_from_inertia(inertia), p.omega[i], omega_dot);
}

GridStress empty_grid_stress(int cells, double cell_volume) {
  GridStress g;
  g.cell_volume = cell_volume;
  for (auto& s : g.sigma) s.assign(cells, Mat3::Zero());
  g.particles.assign(cells, 0);
  g.internal_contacts.assign(cells, 0);
  g.external_contacts.assign(cells, 0);
  g.wall_contacts.assign(cells, 0);
  g.solid_fraction.assign(cells, 0.0);
  return g;
}

void finish_cell(GridStress& g, int c, const StressSums& s, double v) {
  const double inv_v = 1.0 / v;
  auto set = [&](StressFormula f, const Mat3& m) { g.sigma[static_cast<int>(f)][c] = m * inv_v; };
  set(StressFormula::weber, s.weber);
  set(StressFormula::drescher, s.drescher);
  set(StressFormula::bagi, s.bagi);
  set(StressFormula::de_saxce, s.de_saxce - s.inertial);
  set(StressFormula::nicot, s.weber - s.inertial);
  set(StressFormula::modified_nicot, s.bagi - s.inertial);
  // (7): integral rho y (x) a over a rigid grain is the same D (rigid_body_inertia.h), so
  // for rigid grains (6) and (7) coincide term by term.
  set(StressFormula::modified_de_saxce, s.bagi - s.inertial);
  g.particles[c] = s.particles;
  g.internal_contacts[c] = s.internal_contacts;
  g.external_contacts[c] = s.external_contacts;
  g.wall_contacts[c] = s.wall_contacts;
  g.solid_fraction[c] = s.solid_volume * inv_v;
}

std::vector<StressSums> cell_stress_sums(const ParticleStore& p, std::size_t n_counted,
                                         const std::vector<ContactSample>& contacts,
                                         const std::vector<int>& cell, const std::vector<Vec3>& centre,
                                         const GrainDynamics& dynamics) {
  std::vector<StressSums> sums(centre.size());
  for (std::size_t i = 0; i < n_counted; ++i)
    if (cell[i] >= 0) add_grain_count(sums[cell[i]], p.volume(i));
  for (const ContactSample& s : contacts) {
    const int ca = cell[s.a];
    if (s.with_wall()) {
      if (ca >= 0) {
        add_external_contact(sums[ca], s.point, p.x[s.a], s.force_on_a, centre[ca]);
        ++sums[ca].wall_contacts;
      }
      continue;
    }
    const int cb = cell[s.b];
    if (ca >= 0 && ca == cb) {
      add_internal_contact(sums[ca], s.force_on_a, p.x[s.a], p.x[s.b]);
      ++sums[ca].internal_contacts;
      continue;
    }
    if (ca >= 0) {
      add_external_contact(sums[ca], s.point, p.x[s.a], s.force_on_a, centre[ca]);
      ++sums[ca].external_contacts;
    }
    if (cb >= 0) {
      add_external_contact(sums[cb], s.point, p.x[s.b], -s.force_on_a, centre[cb]);
      ++sums[cb].external_contacts;
    }
  }
  for (std::size_t i = 0; i < n_counted; ++i) {
    if (cell[i] >= 0) add_grain_terms(sums[cell[i]], p, i, centre[cell[i]], dynamics);
  }
  return sums;
}

CellAssignment assign_cells(const RegularGrid& grid, const std::vector<Vec3>& x) {
  CellAssignment a;
  a.cell.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) a.cell[i] = grid.cell_of(x[i]);
  a.centre.resize(static_cast<std::size_t>(grid.num_cells()));
  for (int c = 0; c < grid.num_cells(); ++c) a.centre[c] = grid.cell_centre(c);
  return a;
}

GridStress grid_stress(const ParticleStore& p, const std::vector<ContactSample>& contacts,
                       const RegularGrid& grid, const GrainDynamics& dynamics) {
  const int cells = grid.num_cells();
  GridStress g = empty_grid_stress(cells, grid.cell_volume());
  const CellAssignment a = assign_cells(grid, p.x);
  const std::vector<StressSums> sums = cell_stress_sums(p, p.size(), contacts, a.cell, a.centre, dynamics);
  for (int c = 0; c < cells; ++c) finish_cell(g, c, sums[c], g.cell_volume);
  return g;
}

}  // namespace upgrain::dem
