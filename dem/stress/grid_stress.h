#pragma once
// Average Cauchy stress over the cells of a fixed grid from the recorded contacts, by the
// static formulas of the paper brief, section 2 (sigma_ij = (1/V) sum f_i l_j; compression
// negative):
//   Weber (1):    internal contacts, f on a, l = x_b - x_a (centroid to centroid);
//   Drescher (2): external contacts, f on the inside particle, l = x^c (absolute point);
//   Bagi (3):     internal as Weber, plus external contacts with f on the inside particle
//                 and l = x^c - x_inside (centroid to contact point, walls included).
// Internal: both centroids in the cell; external: one centroid in it, or a wall contact
// (brief section 6). Bagi equals the sum over the cell's particles of
// sum_c f^pc (x^c - x^p), so it is additive over cells and its skew part is
// -eps_ijk T_k / (2V) with T the total contact torque on the cell's particles.
// The dynamic formulas (Nicot, De Saxce and the modified forms) come later (issue 7).
#include <vector>

#include "dem/contact/contact_sample.h"
#include "dem/core/particle_store.h"

namespace upgrain::dem {

struct RegularGrid {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Ones();
  int n[3] = {1, 1, 1};

  [[nodiscard]] int num_cells() const { return n[0] * n[1] * n[2]; }
  [[nodiscard]] double cell_volume() const { return (hi - lo).prod() / static_cast<double>(num_cells()); }
  // Cell of a point (half-open cells), or -1 outside the grid.
  [[nodiscard]] int cell_of(const Vec3& x) const;
};

struct GridStress {
  std::vector<Mat3> weber, drescher, bagi;  // one per cell, V = cell volume
  std::vector<long> particles;              // centroids in the cell
  std::vector<long> internal_contacts;
  std::vector<long> external_contacts;  // wall contacts included
  double cell_volume = 0.0;
};

GridStress static_grid_stress(const ParticleStore& p, const std::vector<ContactSample>& contacts,
                              const RegularGrid& grid);

}  // namespace upgrain::dem
