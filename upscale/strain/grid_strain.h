#pragma once
// Finite-strain measures per cell of a regular grid (docs/strain.md "Grids").
//
// A reference snapshot holds the particles' positions at the reference time t0 by global
// id, and the grid of that instant. At each evaluation a cell's particle set is either
//   - Lagrangian: the particles whose centroid was in the cell at t0 (reference grid),
//     followed by global id to their current positions, or
//   - Eulerian: the particles whose centroid is in the cell now (current grid), with their
//     positions at t0.
// Over the set, F (reference -> current positions) and L (current positions -> velocities)
// are taken both ways: the best-fit affine map (deformation_fit.h) and the equivalent
// continuum of the Delaunay tessellation (equivalent_continuum.h). The measures of F
// (strain_measures.h) and of L follow, and the incremental F_inc = F_now F_prev^-1 from the
// previous evaluation.
//
// Nothing here is NaN: a cell whose result cannot be had is marked with a StrainReason and
// all its fields of that result are zero.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "dem/core/periodic_cell.h"
#include "dem/core/types.h"
#include "dem/stress/grid_stress.h"
#include "upscale/strain/equivalent_continuum.h"

namespace upgrain::upscale {

using dem::GlobalId;
using dem::Mat3;
using dem::RegularGrid;
using dem::Vec3;

enum class StrainSet { lagrangian, eulerian };
std::string_view name_of(StrainSet s);  // "lagrangian", "eulerian"

enum class StrainDefinition { best_fit, tessellation };
inline constexpr int kStrainDefinitionCount = 2;
std::string_view name_of(StrainDefinition d);  // "best fit", "tessellation"

// Why a cell's F, L or F_inc is not valid. Written to files as the integer code; the names
// (name_of) are written beside them.
enum class StrainReason : std::int32_t {
  valid = 0,
  too_few_particles = 1,      // fewer than kMinFitPoints (4) in the set
  degenerate_set = 2,         // coplanar, collinear or coincident positions
  non_positive_jacobian = 3,  // J = det F <= 0: an inverted or collapsed cell
  near_singular = 4,          // smallest principal stretch < kMinStretchRatio x largest
  non_finite = 5,             // a position, velocity or result is not finite
  previous_invalid = 6,       // F_inc only: the previous evaluation's F of the cell is not valid
  no_history = 7,             // stress rates only: no earlier output with a stress to difference
};
inline constexpr int kStrainReasonCount = 8;
std::string_view name_of(StrainReason r);

// The state at t0, sorted by global id.
struct StrainReference {
  double time = 0.0;
  long step = 0;
  RegularGrid grid;          // the grid at t0: it defines the Lagrangian sets (unused for other cells)
  int cells = 0;             // the number of cells (sets)
  std::vector<GlobalId> id;  // ascending
  std::vector<Vec3> x;       // position at t0
  std::vector<int> cell;     // cell of x at t0, -1 outside every cell
  // A periodic cell's image counters at t0 (periodic_kinematics.h); empty for a bounded box.
  std::vector<dem::ImageCount> image;
  // A deforming cell's matrix h at t0 (cell_deformation.h); zero for any other.
  Mat3 cell_matrix = Mat3::Zero();
};

// Throws upgrain::Error on repeated ids or spans of different lengths.
StrainReference make_strain_reference(std::span<const GlobalId> id, std::span<const Vec3> x,
                                      const RegularGrid& grid, double time, long step);
// The same for cells that are not those of a grid (the MPI blocks: cell = the block that holds
// the particle): `cell` gives each particle's cell in [0, cells), or -1.
StrainReference make_strain_reference(std::span<const GlobalId> id, std::span<const Vec3> x,
                                      std::span<const int> cell, int cells, double time, long step);

// The current particle state (any order).
struct ParticleKinematics {
  std::span<const GlobalId> id;
  std::span<const Vec3> x;
  std::span<const Vec3> v;
};

// When the current state is: its simulated time (s) and step.
struct StateInstant {
  double time = 0.0;
  long step = 0;
};

struct GridStrainOptions {
  StrainSet set = StrainSet::lagrangian;
  std::array<bool, kStrainDefinitionCount> definitions = {true, true};  // [StrainDefinition]
};

// One definition's results, one entry per cell (cell order of RegularGrid).
struct CellStrainFields {
  std::vector<Mat3> deformation_gradient;  // F
  std::vector<Mat3> velocity_gradient;     // L
  std::vector<Mat3> increment;             // F_inc = F F_prev^-1
  std::vector<Mat3> green_lagrange;        // E
  std::vector<Mat3> euler_almansi;         // e
  std::vector<Mat3> hencky;                // ln V (current frame)
  std::vector<Mat3> rotation;              // R of F = R U
  std::vector<Mat3> rate_of_deformation;   // D = sym L
  std::vector<Mat3> spin;                  // W = skew L
  std::vector<double> jacobian;            // J = det F
  std::vector<double> log_jacobian;        // ln J
  std::vector<double> equivalent_shear_strain;
  std::vector<double> equivalent_shear_rate;
  std::vector<double> increment_log_jacobian;
  std::vector<double> increment_equivalent_shear_strain;
  // Best fit: rms distance of the current positions from the affine map (non-affine part);
  // zero for the tessellation.
  std::vector<double> residual_rms;
  std::vector<StrainReason> f_reason;          // F and its measures
  std::vector<StrainReason> l_reason;          // L, D, W, equivalent shear rate
  std::vector<StrainReason> increment_reason;  // F_inc and its measures

  void resize(int cells);
};

// The Delaunay tetrahedra of one cell's reference positions, kept from one evaluation to
// the next: while a cell's set is the same (always for a Lagrangian set that loses no
// particle), the tessellation's F needs no new tessellation, which halves its cost
// (docs/strain.md "Cost"). F is bitwise the same either way.
struct CellTessellation {
  std::vector<GlobalId> ids;  // the set, in id order
  DelaunayTetrahedra tetrahedra;
};

struct GridStrain {
  StrainSet set = StrainSet::lagrangian;
  double reference_time = 0.0;
  long reference_step = 0;
  double time = 0.0;
  long step = 0;
  // The grid whose cells define the sets: the reference grid (Lagrangian) or the current
  // grid (Eulerian).
  RegularGrid grid;
  std::vector<long> particles;  // size of each cell's set
  // Lagrangian: reference particles in the grid at t0 that no longer exist; Eulerian:
  // particles in the grid now that have no reference position.
  long untracked = 0;
  std::array<bool, kStrainDefinitionCount> computed = {false, false};
  std::array<CellStrainFields, kStrainDefinitionCount> fields;
  // Per cell, with the tessellation: the reference tessellation used (shared with the
  // evaluations that reuse it); null for sets of fewer than 4.
  std::vector<std::shared_ptr<const CellTessellation>> reference_tessellations;

  [[nodiscard]] const CellStrainFields& operator[](StrainDefinition d) const {
    return fields[static_cast<int>(d)];
  }
};

// Evaluates every cell. `previous` (the last evaluation from the same reference, same cell
// count) gives F_prev for the increment; without it F_prev = 1, so F_inc = F. Its reference
// tessellations are reused for the cells whose set has not changed.
// `placed`: where the Eulerian sets place each grain of `now` in the current grid, when not at
// now.x (a periodic cell's wrapped positions, now.x being followed across the faces:
// periodic_kinematics.h); empty: now.x.
GridStrain grid_strain(const StrainReference& reference, const RegularGrid& current_grid,
                       const ParticleKinematics& now, const StateInstant& when,
                       const GridStrainOptions& options, const GridStrain* previous = nullptr,
                       std::span<const Vec3> placed = {});

// The same over any partition into reference.cells sets: Lagrangian sets from reference.cell,
// Eulerian ones from `current_cell` (the cell of each particle of `now`, -1 for none, below
// reference.cells: the current partition has the reference's number of sets). The result's
// grid is left empty. grid_strain() is this with the cells of a RegularGrid.
GridStrain partition_strain(const StrainReference& reference, std::span<const int> current_cell,
                            const ParticleKinematics& now, const StateInstant& when,
                            const GridStrainOptions& options, const GridStrain* previous = nullptr);

}  // namespace upgrain::upscale
