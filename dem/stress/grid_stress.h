#pragma once
// Average Cauchy stress over the cells of a fixed grid, by all seven formulas of the paper
// brief, section 2, from the contacts recorded in one force evaluation and the particles'
// state at that instant. Convention: sigma_ij = (1/V) sum f_i l_j (force index first, so
// that t_i = sigma_ij n_j), compression negative, V the cell volume. docs/stress.md.
//
// Classification (brief section 6): a particle belongs to the cell holding its centroid;
// a contact is internal to a cell when both centroids are in it, and external to each cell
// that holds exactly one of them (force on that particle, branch from its centroid to the
// contact point); wall contacts are external. So a contact is counted once per cell and
// never missed.
#include <array>
#include <vector>

#include "dem/contact/contact_sample.h"
#include "dem/core/particle_store.h"
#include "dem/stress/stress_formula.h"

namespace upgrain::dem {

struct RegularGrid {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Ones();
  int n[3] = {1, 1, 1};

  [[nodiscard]] int num_cells() const { return n[0] * n[1] * n[2]; }
  [[nodiscard]] double cell_volume() const { return (hi - lo).prod() / static_cast<double>(num_cells()); }
  // Cell of a point (half-open cells), or -1 outside the grid. Index (k ny + j) nx + i.
  [[nodiscard]] int cell_of(const Vec3& x) const;
  [[nodiscard]] Vec3 cell_centre(int cell) const;
};

// The state the dynamic formulas need besides positions and contacts.
struct GrainDynamics {
  Vec3 gravity = Vec3::Zero();
  // False when the scene does not integrate rotation: grains then neither spin nor
  // accelerate in rotation, and the inertial terms are zero.
  bool rotation = true;
};

struct GridStress {
  std::array<std::vector<Mat3>, kStressFormulaCount> sigma;  // [formula][cell]
  std::vector<long> particles;                               // centroids in the cell
  std::vector<long> internal_contacts;
  std::vector<long> external_contacts;  // particle contacts across the cell's boundary
  std::vector<long> wall_contacts;
  // Volume of the grains whose centroids are in the cell over the cell volume (grains
  // assigned whole by centroid, so it can exceed the true local value at cell faces).
  std::vector<double> solid_fraction;
  double cell_volume = 0.0;

  [[nodiscard]] const std::vector<Mat3>& operator[](StressFormula f) const {
    return sigma[static_cast<int>(f)];
  }
};

GridStress grid_stress(const ParticleStore& p, const std::vector<ContactSample>& contacts,
                       const RegularGrid& grid, const GrainDynamics& dynamics);

}  // namespace upgrain::dem
