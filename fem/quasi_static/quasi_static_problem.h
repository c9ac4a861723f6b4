#pragma once
// A quasi-static boundary value problem on a box whose material is a state per quadrature point
// (point_state.h): 2D plane strain in x-y or 3D, small strain, solved load step by load step by
// Newton's method with the points' tangents (docs/femxdem.md, "The continuum"). The points are
// the DEM cells of FEM x DEM, or closed-form stand-ins. This header is deal.II-free; deal.II
// lives in quasi_static_solver.cc.
#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "fem/quasi_static/point_state.h"

namespace upgrain::fem {

// What holds a face of the box. A platen moves along the face's normal by the load's
// displacement; a rough one holds the tangential components at zero, a smooth one leaves them
// free. A roller holds the normal component at zero; `fixed` holds every component; an `affine`
// face follows the homogeneous displacement u = G x of the problem's boundary gradient, every
// component (a specimen whose whole boundary is affine can only deform homogeneously, whatever its
// material's anisotropy: the test of a mesh of identical points).
enum class FaceSupport { free, pressure, roller, fixed, smooth_platen, rough_platen, affine };

struct FaceCondition {
  FaceSupport support = FaceSupport::free;
  double pressure = 0.0;  // pressure: the traction -p n (Pa, > 0 pushes on the face)
};

struct QuasiStaticProblem {
  int dimension = 2;                          // 2: plane strain in x-y (per unit thickness along z); 3
  std::array<double, 3> size{1.0, 1.0, 1.0};  // the box [0, size] (m)
  std::array<unsigned, 3> cells{1, 1, 1};     // subdivisions per axis
  unsigned degree = 1;                        // FE_Q degree of the displacement
  // Gauss points per direction in each cell (0: degree + 1, the full rule); one point per cell is
  // the reduced rule of a Q1 element, one DEM cell per element.
  unsigned quadrature_points = 0;
  // Faces 2d (x_d = 0) and 2d + 1 (x_d = size_d), as deal.II's colorized boxes number them.
  std::array<FaceCondition, 6> faces{};
  // The body force rho g; a point whose state has a density of its own (PointState::density)
  // uses that one.
  double density = 0.0;                          // (kg/m^3)
  std::array<double, 3> gravity{0.0, 0.0, 0.0};  // (m/s^2)
  // false: the body force is applied whole at step 0. true: it grows with the load factor, from
  // nothing at step 0 to whole at the last step, as the weight of a column that settles under
  // gravity is taken up (a body whose points start from a stress of their own that does not
  // balance the weight, and whose path to it matters: a granular column's K0). The points' first
  // answers, at step 0, are then taken as balanced, with the pressures on the faces, as a
  // geotechnical analysis takes its initial stresses: the loads act on the change from them
  // (internal forces of sigma - sigma_0 against the body force), so the scatter of stresses of
  // their own (prepared DEM cells: a few per cent of shear stress, which no face holds) is not a
  // load that Newton would have to work off through the cells' noise. Step 0 does not iterate.
  bool body_force_follows_load = false;
  // The platens' displacement along their outward normal at the end of the loading (m; < 0
  // pushes into the body), reached in `load_steps` equal steps after an equilibrium step 0 that
  // applies the body force and the pressures.
  double platen_displacement = 0.0;
  // The displacement gradient G of the affine faces at the end of the loading, reached with the
  // platens' displacement (u = lambda G x, lambda = 0 at step 0 and 1 at the end).
  Mat3x3 boundary_gradient = Mat3x3::Zero();
  unsigned load_steps = 1;
  // Newton converges when the out-of-balance force is below `residual_tolerance` times the
  // internal force (both Euclidean norms over the degrees of freedom), or the correction below
  // `correction_tolerance` times the step's displacement increment (the criterion of Guo and
  // Zhao 2014 for noisy DEM stresses; 0: not used).
  double residual_tolerance = 1e-10;
  double correction_tolerance = 0.0;
  unsigned max_newton_iterations = 25;
  // Halvings of a Newton correction that a point cannot answer or that does not decrease the
  // out-of-balance force, before the iteration goes on with the best fraction (or the step fails
  // when no fraction can be answered): a backtracking line search; 0: plain Newton.
  unsigned line_search_halvings = 3;
  // A load step that fails (a point that does not converge, or Newton) is retried with half its
  // increment, up to this many times in a row.
  unsigned max_step_cuts = 4;
  // The ranks' balance (docs/femxdem.md, "Balancing the ranks"): after a load step in which the
  // busiest rank's points cost more than this times the ranks' mean (PointResponse::cost), the
  // mesh is repartitioned with each cell weighted by its points' cost in that step, and the
  // points move with their cells (PointState::save). Whole cells split the cost only so finely:
  // the threshold applies to the least imbalance they allow (the costliest cell's cost over the
  // ranks' mean) and to the imbalance of the last repartition's weights over its partition, when
  // these are above 1. 0: never.
  double rebalance_threshold = 1.1;
};

using PointFactory = std::function<std::unique_ptr<PointState>(const PointPlace&)>;

// One load step as it converged.
struct LoadStepRecord {
  unsigned step = 0;                 // 0: the equilibrium step
  double platen_displacement = 0.0;  // m
  double platen_force = 0.0;         // the platens' reaction along their outward normal (N; per
                                     // unit thickness in 2D, N/m), averaged over the platens
  unsigned newton_iterations = 0;
  std::vector<double> residuals;      // the relative out-of-balance force at each iteration
  unsigned cuts = 0;                  // halvings before it converged
  unsigned line_search_halvings = 0;  // of its Newton corrections, over all its attempts
  double cost = 0.0;                  // the points' cost (point_state.h), summed over the ranks
  // The busiest rank's share of `cost` over the ranks' mean (1: even, or nothing cost anything),
  // in the partition the step ran on; and whether the mesh was repartitioned by cost after it.
  double imbalance = 1.0;
  bool repartitioned = false;
  double seconds = 0.0;  // wall time of the step, the slowest rank's
};

// A point's committed state, gathered on every rank in the order of the cells' ids.
struct PointSummary {
  PointPlace place;
  Vec6 stress = Vec6::Zero();
  Mat3x3 displacement_gradient = Mat3x3::Zero();
  double density = 0.0;          // the body force's (PointState::density, else the problem's)
  std::vector<double> measures;  // PointState::measures(), named by the problem's measure names
};

struct QuasiStaticResult {
  std::vector<LoadStepRecord> steps;
  std::vector<PointSummary> points;        // at the end
  std::vector<std::string> measure_names;  // the points' PointState::measures()
  std::uint64_t n_dofs = 0;
  std::uint64_t n_cells = 0;
};

// What to write: each converged step's displacement, cell-averaged stress and strain, q/p, the
// points' measures and the ranks that own the cells after the step (`subdomain`) as
// `name`-NNNN.pvtu in `folder` (nothing when empty).
struct QuasiStaticOutput {
  std::string folder;
  std::string name = "continuum";
  // Called on every rank after each converged step (a progress line).
  std::function<void(const LoadStepRecord&)> on_step;
  // Called on every rank after each converged step with every point's committed state
  // (collective: gathered only when set) and the measures' names.
  std::function<void(const LoadStepRecord&, const std::vector<std::string>& measure_names,
                     const std::vector<PointSummary>&)>
      on_points;
  // Called on every rank after each converged step, before on_points, with the place and the
  // committed state of each point the rank owns (collective: the caller may gather). A DEM cell's
  // grains are written for a viewer this way, where the cell is.
  std::function<void(const LoadStepRecord&, const std::vector<std::pair<PointPlace, const PointState*>>&)>
      on_owned_points;
};

// Checkpoints of the solver's whole state (docs/femxdem.md, "Checkpoints and restart"): the mesh
// and its partition, the committed displacement, every point's committed state and answer
// (PointState::save), and the steps converged so far. They are the files that deal.II's
// Triangulation::save writes under a stem (the stem itself, stem.info, stem_fixed.data,
// stem_variable.data) and stem.solver, on a file system that every rank reaches; give each
// checkpoint a folder of its own and keep all its files. A solve of the same problem resumed from
// them on the same rank count continues with the same bits; on another, p4est partitions the
// cells anew and the path agrees to round-off (the matrix is summed in another order).
struct QuasiStaticCheckpoints {
  // Called on every rank after each converged step, once its output is written: the stem to save
  // the state under, or empty for none. It must be the same on every rank.
  std::function<std::string(const LoadStepRecord&)> stem;
  // Called on every rank once the state is saved under `stem`. The caller may take the files and
  // stop the solve by throwing (on every rank alike).
  std::function<void(const LoadStepRecord&, const std::string& stem)> saved;
  // The stem of a state saved by a solve of the same problem, to continue from; empty: from the
  // start (step 0).
  std::string resume;
  // Called on every rank once the state is restored, with the steps it had converged (the step
  // records of QuasiStaticResult::steps so far), before the first new step.
  std::function<void(const std::vector<LoadStepRecord>&)> resumed;
  // Asked on every rank after the points have answered an assembly (local and cheap: a signal's
  // flag). When any rank says yes, the step in progress is abandoned and the state of the last
  // converged step is saved at once (`stem` and `saved` as after a step; `saved` is expected to
  // stop the solve by throwing), so that a stop is served within one round of the points'
  // answers, not at the end of a load step that may take minutes: a launcher or a batch system
  // kills what has not stopped within seconds (Open MPI's mpirun within 1 s, Slurm's KillWait 30 s
  // by default). Points may cut their answers short meanwhile; those answers are dropped.
  std::function<bool()> stop_requested;
};

// Throws std::invalid_argument naming the first bad parameter.
void validate(const QuasiStaticProblem& problem);

// Solves the problem on the ranks of `comm` (collective), each rank's points made by `make_point`
// on the rank that owns their cell. Throws std::runtime_error naming the load step, the cell and
// the point when a step still fails after its cuts, or naming the stem when a state to resume
// from is not of this problem or cannot be read.
QuasiStaticResult solve_quasi_static(const QuasiStaticProblem& problem, const PointFactory& make_point,
                                     MPI_Comm comm, const QuasiStaticOutput& output = {},
                                     const QuasiStaticCheckpoints& checkpoints = {});

}  // namespace upgrain::fem
