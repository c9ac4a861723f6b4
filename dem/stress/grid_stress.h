#pragma once
// Average Cauchy stress over the cells of a fixed grid, by all seven formulas of Yan and Regueiro's paper
// paper (section 2), from the contacts recorded in one force evaluation and the particles'
// state at that instant. Convention: sigma_ij = (1/V) sum f_i l_j (force index first, so
// that t_i = sigma_ij n_j), compression negative, V the cell volume. docs/stress.md.
//
// Classification (Yan and Regueiro): a particle belongs to the cell holding its centroid;
// a contact is internal to a cell when both centroids are in it, and external to each cell
// that holds exactly one of them (force on that particle, branch from its centroid to the
// contact point); wall contacts are external. So a contact is counted once per cell and
// never missed.
#include <array>
#include <vector>

#include "dem/contact/contact_sample.h"
#include "dem/core/box.h"
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
  // Per-cell volumes when the cells differ (compute grids, dem/parallel/parallel_stress.h);
  // empty when every cell has cell_volume.
  std::vector<double> volume;

  [[nodiscard]] const std::vector<Mat3>& operator[](StressFormula f) const {
    return sigma[static_cast<int>(f)];
  }
};

GridStress grid_stress(const ParticleStore& p, const std::vector<ContactSample>& contacts,
                       const RegularGrid& grid, const GrainDynamics& dynamics);

// The stress of the compute grids (the blocks of an MPI decomposition, one cell per block):
// `stress` has a cell per block and per-cell volumes, `block` the blocks clipped to the
// decomposition box (dem/parallel/parallel_stress.h).
struct ComputeGridStress {
  GridStress stress;
  std::vector<Box> block;
};

// The building blocks of grid_stress(), shared with the parallel evaluation
// (dem/parallel/parallel_stress.h), which sums the same terms per grain.
//
// The raw sums of one cell, or one grain's share of a cell, before the division by V
// (force index first). `inertial` is the grains' rotational inertial moment D; the
// formulas built on it (Nicot, the modified forms, De Saxce's body term) are assembled by
// finish_cell().
struct StressSums {
  Mat3 weber = Mat3::Zero();
  Mat3 drescher = Mat3::Zero();
  Mat3 bagi = Mat3::Zero();
  Mat3 de_saxce = Mat3::Zero();
  Mat3 inertial = Mat3::Zero();
  long particles = 0;
  long internal_contacts = 0;
  long external_contacts = 0;
  long wall_contacts = 0;
  double solid_volume = 0.0;

  StressSums& operator+=(const StressSums& o);
};

// An internal contact: f (on a) (x) (x_b - x_a), Weber's and Bagi's term.
inline void add_internal_contact(StressSums& s, const Vec3& force_on_a, const Vec3& x_a, const Vec3& x_b) {
  const Mat3 t = force_on_a * (x_b - x_a).transpose();
  s.weber += t;
  s.bagi += t;
}

// An external contact seen from the inside grain q at x_q, which receives force f at
// `point`. De Saxce's absolute positions are taken from the cell centre: the formula is
// translation invariant (its body term balances the contact forces), and this keeps the
// sums free of cancellation far from the origin. Drescher's is not invariant and keeps
// the scene's origin, as published.
inline void add_external_contact(StressSums& s, const Vec3& point, const Vec3& x_q, const Vec3& f,
                                 const Vec3& centre) {
  s.drescher += f * point.transpose();
  s.bagi += f * (point - x_q).transpose();
  s.de_saxce += f * (point - centre).transpose();
}

// One grain's own terms: De Saxce's body term integral rho (g - a) (x) x dV =
// m (g - a^p) (x) x^p - D, where m (a^p - g) is the grain's total contact force, and the
// rotational inertial moment D (rigid_body_inertia.h). Counts and solid volume are added
// by add_grain_count().
void add_grain_terms(StressSums& s, const ParticleStore& p, std::size_t i, const Vec3& centre,
                     const GrainDynamics& dynamics);
void add_grain_count(StressSums& s, double volume);

// The cell of every particle of `x` (-1 outside the grid) and the centre of every cell.
struct CellAssignment {
  std::vector<int> cell;
  std::vector<Vec3> centre;
};
CellAssignment assign_cells(const RegularGrid& grid, const std::vector<Vec3>& x);

// The sums of every cell from contacts (each once) over any partition of the particles:
// cell[i] is the cell of local particle i (-1: none), centre[c] the reference point of cell c
// for De Saxce's terms. Particles [0, n_counted) add their counts and own terms; the others
// (ghosts) only classify the contacts they take part in. grid_stress() is this over a whole
// store; the fast summation of the MPI engine sums it over the ranks.
std::vector<StressSums> cell_stress_sums(const ParticleStore& p, std::size_t n_counted,
                                         const std::vector<ContactSample>& contacts,
                                         const std::vector<int>& cell, const std::vector<Vec3>& centre,
                                         const GrainDynamics& dynamics);

// Writes cell c of g (arrays already sized) from its sums over a cell of volume v.
void finish_cell(GridStress& g, int c, const StressSums& s, double v);
// A GridStress with all arrays sized for `cells` cells, zero.
GridStress empty_grid_stress(int cells, double cell_volume);

}  // namespace upgrain::dem
