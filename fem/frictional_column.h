#pragma once
// The continuum counterpart of a DEM bed in a box whose walls have friction (docs/fem.md,
// "Frictional walls" and "Drucker–Prager elastoplasticity"): a gravity-loaded column,
// elastic or Drucker–Prager, in a rigid box whose side walls (and optionally floor) hold the
// normal displacement and carry Coulomb friction. Solved by Newton's method in load steps
// on a distributed mesh. Like elastic_column.h this header is deal.II-free: deal.II lives in
// frictional_column.cc only.
#include <mpi.h>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/elastic_column.h"
#include "fem/plasticity/drucker_prager.h"

namespace upgrain::fem {

enum class ColumnMaterial { elastic, drucker_prager };

// Mohr–Coulomb strength of the Drucker–Prager continuum. Angles in degrees.
struct MohrCoulombStrength {
  double friction_angle_deg = 30.0;  // phi, (0, 90)
  double dilatancy_angle_deg = 0.0;  // psi, [0, phi]
  double cohesion = 0.0;             // c (Pa), >= 0
  ConeMatching matching = ConeMatching::outer;
};

// Coulomb friction of the rigid container. A coefficient of 0 is a frictionless roller.
struct WallFriction {
  // Side walls x = 0, x = Lx, y = 0, y = Ly (the order of the DEM container's walls).
  std::array<double, 4> side = {0.0, 0.0, 0.0, 0.0};
  double floor = 0.0;
  // The tangential penalty eps_T = penalty_factor * G / h_n, with G the continuum's shear
  // modulus and h_n the wall cell's size normal to the wall: a stick zone then slips
  // elastically as much as a layer of the material 1/penalty_factor of a cell thick would
  // shear. Where the wall slips the answer does not depend on it.
  double penalty_factor = 100.0;
};

// How the load is applied.
struct ColumnLoading {
  // Gravity is raised to its full value in this many equal steps (Newton in each).
  unsigned load_steps = 5;
  // Staged construction: the column is built in layers of one cell each, bottom to top;
  // each layer is placed stress-free on the deformed column below and loads it with its
  // weight in one step (load_steps is then unused).
  bool staged_construction = false;
  // Lateral relaxation after gravity: the walls x = Lx and y = Ly are moved outwards by
  // these displacements (m, >= 0) in relaxation_steps equal steps. 0 = walls stay.
  std::array<double, 2> wall_displacement = {0.0, 0.0};
  unsigned relaxation_steps = 0;
};

struct NewtonControl {
  // Converged when the residual's l2 norm is below tolerance * |f|, |f| the norm of the full
  // gravity load vector.
  double tolerance = 1e-9;
  unsigned max_iterations = 25;
  bool log = false;  // print |r|/|f| of every Newton iteration on rank 0
};

struct FrictionalColumnProblem {
  ColumnProblem column;  // box, fill, density, gravity, E, nu, mesh, degree
  ColumnMaterial material = ColumnMaterial::elastic;
  MohrCoulombStrength strength;  // used when material == drucker_prager
  WallFriction walls;
  ColumnLoading loading;
  NewtonControl newton;
};

struct LoadStepLog {
  // Residual norm relative to |f| at each Newton iteration, the initial one first.
  std::vector<double> residuals;
  std::vector<unsigned> linear_iterations;  // GMRES iterations of each Newton step
};

// Every field holds the same value on every rank, except the timings (the calling rank's).
struct FrictionalColumnSolution {
  // As ColumnSolution: the volume average of sigma over each coarse cell, row-major 3x3,
  // compression negative, index coarse_cell_index().
  std::vector<std::array<double, 9>> cell_average_stress;
  double weight = 0.0;                    // rho g Lx Ly H (N)
  double side_wall_vertical_force = 0.0;  // upward force of the side walls on the fill (N)
  // The same per level of the coarse mesh (problem.column.cells[2] levels of equal height,
  // from the floor up): the wall shear against height (N per level; they sum to the total).
  std::vector<double> side_wall_vertical_force_by_level;
  // Upward force of the floor, -int sigma_zz dA at the floor (N). With the side walls' it
  // balances the weight up to the discretisation error.
  double floor_vertical_force = 0.0;
  // Side-wall area (by quadrature weight) where the friction is at its limit mu p, as a
  // share of the side-wall area where p > 0 and mu > 0. 1 = the walls slip everywhere.
  double slipping_wall_share = 0.0;
  double plastic_volume_share = 0.0;  // volume share of points that yielded in the last step
  std::vector<LoadStepLog> load_steps;
  std::uint64_t n_dofs = 0;
  std::uint64_t n_active_cells = 0;
  unsigned newton_iterations = 0;  // over all load steps
  unsigned bisections = 0;         // load steps cut in two after Newton failed
  unsigned linear_iterations = 0;  // over all Newton steps
  double assemble_seconds = 0.0;
  double solve_seconds = 0.0;  // AMG setup plus GMRES
  double total_seconds = 0.0;
};

// Thrown, on every rank alike, when Newton's method fails in a load step even after the
// step has been bisected: the message names the load step and the residual history.
struct NewtonFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws std::invalid_argument naming the first bad parameter (FrictionalColumnProblem.<field>).
void validate(const FrictionalColumnProblem& problem);

// The Drucker–Prager cone of the problem's strength (radians converted).
DruckerPrager drucker_prager_cone(const MohrCoulombStrength& strength);

// Solves on the ranks of `comm` (collective), writing column.pvtu and its pieces to
// vtu_folder unless it is empty (atomically, as solve_column does). Throws
// std::invalid_argument on bad input (every rank, before any communication), NewtonFailure
// if Newton does not converge, and std::runtime_error if output fails.
FrictionalColumnSolution solve_frictional_column(const FrictionalColumnProblem& problem, MPI_Comm comm,
                                                 const std::string& vtu_folder);

}  // namespace upgrain::fem
