#pragma once
// The FEMxDEM section of a scene file (docs/femxdem.md): the specimen, its mesh and loading, the
// Newton iteration, and the DEM cell at each quadrature point (coupling/femxdem/rve_options.h).
// Each default written here once.
#include <string>

#include "coupling/femxdem/rve_options.h"
#include "fem/quasi_static/quasi_static_problem.h"

namespace upgrain::coupling {

// What loads the specimen (docs/femxdem.md).
enum class FemxdemLoading {
  // Plane-strain compression: the bottom fixed, the top a platen that shortens the specimen by
  // axial_strain, the sides under the confining pressure.
  biaxial,
  // The column under its own weight, as a bed in a box with smooth walls: the sides on rollers,
  // the bottom fixed (a rough floor), the top under the confining pressure (a surcharge that keeps
  // the top cells' grains in contact, as they were prepared); gravity along -y, of the scene's
  // magnitude, grows from nothing in load_steps equal steps, and each point's body force is its
  // cell's density (its grains' mass over its volume).
  gravity_column,
};

struct FemxdemOptions {
  FemxdemLoading loading = FemxdemLoading::biaxial;
  // A biaxial (plane-strain) specimen [0, width] x [0, height] in x-y, per unit thickness along z,
  // as Guo and Zhao's (2014) 50 x 100 mm. 3D needs DEM cells with more than one tilt (planned).
  double width = 0.05;  // m
  double height = 0.1;  // m
  int cells_x = 2;
  int cells_y = 4;
  int degree = 1;
  int quadrature_points = 0;  // per direction; 0: degree + 1
  bool rough_platens = true;
  // The top platen shortens the specimen by this strain in load_steps equal steps; the bottom one
  // is fixed. The sides carry the confining pressure, which is also the DEM cells' initial
  // isotropic stress (RveOptions::mean_stress), so the specimen starts in equilibrium.
  double axial_strain = 0.02;
  int load_steps = 10;
  // Newton: the criteria of fem/quasi_static/quasi_static_problem.h; a DEM cell's stress is only
  // as balanced as its relaxation, so the out-of-balance force stops near its tolerance, and the
  // correction criterion (Guo and Zhao 2014: 1e-2) ends the iteration instead.
  double residual_tolerance = 1e-4;
  double correction_tolerance = 1e-2;
  int max_newton_iterations = 15;
  int line_search_halvings = static_cast<int>(fem::QuasiStaticProblem{}.line_search_halvings);
  int max_step_cuts = 4;
  // The ranks rebalanced by the DEM cells' measured cost (fem/quasi_static/quasi_static_problem.h).
  double rebalance_threshold = fem::QuasiStaticProblem{}.rebalance_threshold;
  // Distinct DEM cells: each Gauss point copies one of this many packings (seeds cell seed, cell
  // seed + 1, ...), chosen by its place; 0: every point its own (coupling/femxdem/rve_packings.h).
  int cell_packings = 1;
  // The DEM cells whose grains are written at every converged load step, for ParaView: "all", or
  // a list of element:point (the element's number, the first of points.csv's cell column, and the
  // Gauss point's index); empty: none.
  std::string cell_snapshots;
  RveOptions rve;
};

}  // namespace upgrain::coupling
