// The nonlinear column: the only other translation unit of upgrain::fem that includes
// deal.II. It reads like deal.II's step-18 (state per quadrature point as a plain struct,
// load steps) and step-42 (plasticity with Newton, Trilinos AMG): one class whose run()
// makes the mesh, sets up the system and, per load step, runs Newton's method, each
// iteration assembling the consistent tangent and the residual and solving with GMRES;
// then it post-processes and writes output, each phase timed by TimerOutput. The physics
// kernels are plain functions: the Drucker–Prager return mapping
// (plasticity/drucker_prager.h) and the Coulomb law of the walls
// (contact/coulomb_friction.h). docs/fem.md derives the equations.
#include "fem/frictional_column.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/generic_linear_algebra.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/lac/vector_memory.h>
#include <deal.II/numerics/vector_tools.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "fem/column_amg.h"
#include "fem/column_mesh.h"
#include "fem/contact/coulomb_friction.h"
#include "fem/material_point.h"

namespace upgrain::fem {

namespace {

using namespace dealii;
namespace LA = dealii::LinearAlgebraTrilinos;
using column_mesh::dim;
using Vector3 = Eigen::Vector3d;

constexpr unsigned int n_walls = 5;  // boundary ids 0-3 the side walls, 4 the floor; 5 is the free top

Vec6 mandel_of(const SymmetricTensor<2, dim>& t) {
  return (Vec6() << t[0][0], t[1][1], t[2][2], mandel::sqrt2 * t[0][1], mandel::sqrt2 * t[0][2],
          mandel::sqrt2 * t[1][2])
      .finished();
}
SymmetricTensor<2, dim> symmetric_tensor_of(const Vec6& a) {
  SymmetricTensor<2, dim> t;
  t[0][0] = a[0];
  t[1][1] = a[1];
  t[2][2] = a[2];
  t[0][1] = a[3] / mandel::sqrt2;
  t[0][2] = a[4] / mandel::sqrt2;
  t[1][2] = a[5] / mandel::sqrt2;
  return t;
}

class FrictionalColumn {
 public:
  FrictionalColumn(const FrictionalColumnProblem& problem, MPI_Comm comm);
  FrictionalColumnSolution run(const std::string& vtu_folder);

 private:
  void make_grid();
  void setup_system();
  void setup_quadrature_point_history();
  void make_constraints(AffineConstraints<double>& constraints, const std::array<double, 2>& wall_increment,
                        unsigned int top_layer) const;
  double gravity_load_norm();
  void assemble_system(double load_factor, const AffineConstraints<double>& constraints);
  unsigned int solve_linear_system(const AffineConstraints<double>& constraints, double relative_residual,
                                   LA::MPI::Vector& newton_update);
  bool newton(double load_factor, const std::array<double, 2>& wall_increment, LoadStepLog& log);
  void solve_load_step(double from, double to, const std::array<double, 2>& wall_increment,
                       unsigned int depth);
  void place_layer(unsigned int layer);
  void commit_state();
  void postprocess();
  void output_results(const std::string& folder) const;

  unsigned int layer_of(const typename DoFHandler<dim>::active_cell_iterator& cell) const;
  bool is_active(const typename DoFHandler<dim>::active_cell_iterator& cell) const {
    return layer_of(cell) <= top_layer_;
  }
  std::vector<WallPoint>::iterator wall_points_of(
      const typename DoFHandler<dim>::active_cell_iterator& cell) {
    return wall_points_.begin() + wall_offset_[cell->active_cell_index()];
  }

  const FrictionalColumnProblem problem_;
  const Elasticity elasticity_;
  const MaterialLaw material_;
  MPI_Comm comm_;
  ConditionalOStream pcout_;

  parallel::distributed::Triangulation<dim> triangulation_;
  const FESystem<dim> fe_;
  DoFHandler<dim> dof_handler_;
  const QGauss<dim> quadrature_;
  const QGauss<dim - 1> face_quadrature_;
  IndexSet locally_owned_dofs_;
  IndexSet locally_relevant_dofs_;
  AffineConstraints<double> newton_constraints_;  // homogeneous: the rollers and unbuilt layers

  LA::MPI::SparseMatrix system_matrix_;
  LA::MPI::Vector system_rhs_;                 // minus the residual
  LA::MPI::Vector locally_relevant_solution_;  // u of the current iterate

  // State per quadrature point of the locally owned cells (step-18), indexed by
  // active_cell_index() * n_q + q; wall points of a cell start at wall_offset_[cell], one
  // block of face quadrature points per wall face in face order.
  std::vector<MaterialPoint> material_points_;
  std::vector<WallPoint> wall_points_;
  std::vector<unsigned int> wall_offset_;

  unsigned int n_layers_ = 1;
  unsigned int top_layer_ = 0;  // the highest layer built so far (staged construction)
  double load_norm_ = 1.0;      // |f|, the l2 norm of the full gravity load

  std::array<Vector<double>, 6> cell_stress_;  // per active cell, for output
  Vector<double> cell_plastic_share_;
  FrictionalColumnSolution result_;
  TimerOutput timer_;
};

FrictionalColumn::FrictionalColumn(const FrictionalColumnProblem& problem, MPI_Comm comm)
    : problem_(problem),
      elasticity_(Elasticity::from_youngs(problem.column.youngs_modulus, problem.column.poisson_ratio)),
      material_(problem.material, elasticity_, drucker_prager_cone(problem.strength)),
      comm_(comm),
      pcout_(std::cout, problem.newton.log && Utilities::MPI::this_mpi_process(comm) == 0),
      triangulation_(comm),
      fe_(FE_Q<dim>(problem.column.degree), dim),
      dof_handler_(triangulation_),
      // Gauss with k + 1 points integrates the Q_k stiffness of an affine cell exactly.
      quadrature_(problem.column.degree + 1),
      face_quadrature_(problem.column.degree + 1),
      // No communicator: as in elastic_column.cc, the library prints nothing and the
      // destructor must not synchronise while an exception unwinds on all ranks.
      timer_(std::cout, TimerOutput::never, TimerOutput::wall_times) {}

unsigned int FrictionalColumn::layer_of(const typename DoFHandler<dim>::active_cell_iterator& cell) const {
  const double z = cell->center()[2] / problem_.column.height;
  return std::min(static_cast<unsigned int>(z * n_layers_), n_layers_ - 1);
}

void FrictionalColumn::make_grid() { column_mesh::make_grid(triangulation_, problem_.column); }

void FrictionalColumn::setup_system() {
  dof_handler_.distribute_dofs(fe_);
  locally_owned_dofs_ = dof_handler_.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler_, locally_relevant_dofs_);
  locally_relevant_solution_.reinit(locally_owned_dofs_, locally_relevant_dofs_, comm_);
  system_rhs_.reinit(locally_owned_dofs_, comm_);

  // Staged construction builds one fine layer of cells at a time. The sparsity pattern is
  // that of the whole column; held dofs of unbuilt layers only use its diagonal.
  n_layers_ =
      problem_.loading.staged_construction ? problem_.column.cells[2] << problem_.column.refinements : 1;
  top_layer_ = problem_.loading.staged_construction ? 0 : n_layers_ - 1;

  AffineConstraints<double> rollers;
  make_constraints(rollers, {0.0, 0.0}, n_layers_ - 1);
  DynamicSparsityPattern dsp(locally_relevant_dofs_);
  DoFTools::make_sparsity_pattern(dof_handler_, dsp, rollers, /*keep_constrained_dofs=*/false);
  SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs_, comm_, locally_relevant_dofs_);
  system_matrix_.reinit(locally_owned_dofs_, locally_owned_dofs_, dsp, comm_);
  make_constraints(newton_constraints_, {0.0, 0.0}, top_layer_);

  result_.n_dofs = dof_handler_.n_dofs();
  result_.n_active_cells = triangulation_.n_global_active_cells();
}

// The container holds the normal displacement of every wall and of the floor (the walls are
// rigid; friction acts tangentially, in the assembly). During a lateral relaxation the walls
// x = Lx and y = Ly move outwards: their normal displacement increases by wall_increment.
// During staged construction the dofs of layers not yet built are held at zero; a dof on
// the top face of the built column is free.
void FrictionalColumn::make_constraints(AffineConstraints<double>& constraints,
                                        const std::array<double, 2>& wall_increment,
                                        const unsigned int top_layer) const {
  constraints.clear();
  constraints.reinit(locally_relevant_dofs_);
  DoFTools::make_hanging_node_constraints(dof_handler_, constraints);
  const std::array<std::tuple<types::boundary_id, unsigned int, double>, n_walls> walls = {
      {{column_mesh::wall_x0, 0, 0.0},
       {column_mesh::wall_x1, 0, wall_increment[0]},
       {column_mesh::wall_y0, 1, 0.0},
       {column_mesh::wall_y1, 1, wall_increment[1]},
       {column_mesh::floor_z0, 2, 0.0}}};
  for (const auto& [boundary, component, value] : walls)
    VectorTools::interpolate_boundary_values(dof_handler_, boundary,
                                             Functions::ConstantFunction<dim>(value, dim), constraints,
                                             fe_.component_mask(FEValuesExtractors::Scalar(component)));
  if (top_layer + 1 < n_layers_) {
    // Ghost cells count too: a dof shared with a built cell of another rank is free. The
    // dofs of owned and ghost cells are the locally relevant ones, indexed within that set.
    std::vector<bool> built(locally_relevant_dofs_.n_elements(), false);
    std::vector<types::global_dof_index> dofs(fe_.n_dofs_per_cell());
    for (const auto& cell : dof_handler_.active_cell_iterators()) {
      if (cell->is_artificial() || layer_of(cell) > top_layer) continue;
      cell->get_dof_indices(dofs);
      for (const auto i : dofs) built[locally_relevant_dofs_.index_within_set(i)] = true;
    }
    for (const auto i : locally_relevant_dofs_)
      if (!built[locally_relevant_dofs_.index_within_set(i)] && !constraints.is_constrained(i))
        constraints.add_line(i);
  }
  constraints.close();
}

// Wall and floor quadrature points of every locally owned cell that touches them, and the
// volume points of every locally owned cell. All start unstressed at u = 0.
void FrictionalColumn::setup_quadrature_point_history() {
  const unsigned int n_q = quadrature_.size(), n_face_q = face_quadrature_.size();
  material_points_.assign(triangulation_.n_active_cells() * n_q, MaterialPoint{});
  wall_offset_.assign(triangulation_.n_active_cells(), 0);
  unsigned int n_wall_points = 0;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    wall_offset_[cell->active_cell_index()] = n_wall_points;
    for (const auto& face : cell->face_iterators())
      if (face->at_boundary() && face->boundary_id() < n_walls) n_wall_points += n_face_q;
  }
  wall_points_.assign(n_wall_points, WallPoint{});
}

// |f| for the relative residual: the full gravity load of the whole column, whatever is
// built or applied at the moment.
double FrictionalColumn::gravity_load_norm() {
  FEValues<dim> fe_values(fe_, quadrature_, update_values | update_JxW_values);
  const unsigned int dofs_per_cell = fe_.n_dofs_per_cell();
  Vector<double> cell_rhs(dofs_per_cell);
  std::vector<types::global_dof_index> dofs(dofs_per_cell);
  AffineConstraints<double> rollers;
  make_constraints(rollers, {0.0, 0.0}, n_layers_ - 1);
  system_rhs_ = 0.0;
  const double body_force_z = -problem_.column.density * problem_.column.gravity;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    cell_rhs = 0.0;
    for (const unsigned int q : fe_values.quadrature_point_indices())
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        if (fe_.system_to_component_index(i).first == 2)
          cell_rhs(i) += body_force_z * fe_values.shape_value(i, q) * fe_values.JxW(q);
    cell->get_dof_indices(dofs);
    rollers.distribute_local_to_global(cell_rhs, dofs, system_rhs_);
  }
  system_rhs_.compress(VectorOperation::add);
  return system_rhs_.l2_norm();
}

// The Newton system at the current iterate u (de Souza Neto et al. 2008, ch. 4): the residual
//   r(u)_i = int sigma(u) : eps(phi_i) dx - load_factor int f . phi_i dx - int_walls t(u) . phi_i dA
// and its derivative K = dr/du, the consistent tangent. Here sigma(u) is the return-mapped
// stress of every volume point, t(u) the Coulomb traction of every wall point, whose limit
// mu p depends on u through the wall point's own normal stress p = -n . sigma(u) . n.
// system_rhs_ receives -r. Cells of layers not yet built contribute nothing but a diagonal
// entry for their held dofs.
void FrictionalColumn::assemble_system(const double load_factor,
                                       const AffineConstraints<double>& constraints) {
  TimerOutput::Scope timer_section(timer_, "assemble");
  system_matrix_ = 0.0;
  system_rhs_ = 0.0;
  FEValues<dim> fe_values(fe_, quadrature_, update_values | update_gradients | update_JxW_values);
  FEFaceValues<dim> fe_face_values(
      fe_, face_quadrature_, update_values | update_gradients | update_normal_vectors | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  const unsigned int n = fe_.n_dofs_per_cell(), n_q = quadrature_.size();
  Eigen::MatrixXd cell_matrix(n, n);
  Eigen::VectorXd cell_rhs(n);
  Eigen::Matrix<double, 6, Eigen::Dynamic> B(6, n);  // Mandel eps(phi_j) at a point
  Eigen::Matrix<double, 3, Eigen::Dynamic> N(3, n);  // phi_j at a point
  FullMatrix<double> local_matrix(n, n);
  Vector<double> local_rhs(n);
  std::vector<types::global_dof_index> dofs(n);
  std::vector<SymmetricTensor<2, dim>> strains(n_q), face_strains(face_quadrature_.size());
  std::vector<Tensor<1, dim>> face_displacements(face_quadrature_.size());
  const Vector3 body_force(0.0, 0.0, -load_factor * problem_.column.density * problem_.column.gravity);
  const auto fill_shape_matrices = [&](const FEValuesBase<dim>& values, unsigned int q) {
    for (unsigned int j = 0; j < n; ++j) {
      B.col(j) = mandel_of(values[displacement].symmetric_gradient(j, q));
      const Tensor<1, dim> phi = values[displacement].value(j, q);
      N.col(j) = Vector3(phi[0], phi[1], phi[2]);
    }
  };

  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    cell->get_dof_indices(dofs);
    if (!is_active(cell)) {
      // A diagonal of the size of the elastic stiffness for the held dofs, which
      // AffineConstraints puts on their rows; the free dofs of this cell belong to built
      // cells, which assemble them.
      local_matrix = 0.0;
      local_rhs = 0.0;
      const double scale =
          (elasticity_.bulk_modulus + 4.0 / 3.0 * elasticity_.shear_modulus) * std::cbrt(cell->measure());
      for (unsigned int i = 0; i < n; ++i)
        if (constraints.is_constrained(dofs[i])) local_matrix(i, i) = scale;
      constraints.distribute_local_to_global(local_matrix, local_rhs, dofs, system_matrix_, system_rhs_);
      continue;
    }
    cell_matrix.setZero();
    cell_rhs.setZero();
    fe_values.reinit(cell);
    fe_values[displacement].get_function_symmetric_gradients(locally_relevant_solution_, strains);
    MaterialPoint* points = &material_points_[cell->active_cell_index() * n_q];
    for (unsigned int q = 0; q < n_q; ++q) {
      fill_shape_matrices(fe_values, q);
      const Vec6 strain = mandel_of(strains[q]);
      const MaterialResponse m = material_.respond(points[q], strain);
      points[q].new_stress = m.stress;
      points[q].new_strain = strain;
      points[q].new_region = m.region;
      const double JxW = fe_values.JxW(q);
      cell_matrix.noalias() += B.transpose() * (m.tangent * JxW) * B;
      cell_rhs.noalias() -= (B.transpose() * m.stress - N.transpose() * body_force) * JxW;
    }

    // Walls and floor: the wall point's material gives p, the Coulomb law the traction.
    auto wall_point = wall_points_of(cell);
    for (const unsigned int f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary() || cell->face(f)->boundary_id() >= n_walls) continue;
      const types::boundary_id wall = cell->face(f)->boundary_id();
      const double mu = wall == column_mesh::floor_z0 ? problem_.walls.floor : problem_.walls.side[wall];
      // eps_T = penalty_factor G / h_n, h_n the cell's size normal to the wall.
      const double penalty =
          problem_.walls.penalty_factor * elasticity_.shear_modulus / cell->extent_in_direction(wall / 2);
      fe_face_values.reinit(cell, f);
      fe_face_values[displacement].get_function_symmetric_gradients(locally_relevant_solution_, face_strains);
      fe_face_values[displacement].get_function_values(locally_relevant_solution_, face_displacements);
      for (unsigned int q = 0; q < face_quadrature_.size(); ++q, ++wall_point) {
        const Tensor<1, dim> nq = fe_face_values.normal_vector(q);
        const Vector3 normal(nq[0], nq[1], nq[2]);
        const Vec6 strain = mandel_of(face_strains[q]);
        const MaterialResponse m = material_.respond(wall_point->material, strain);
        const Vec6 normal_projector = mandel::from_matrix(normal * normal.transpose());
        const double pressure = -normal_projector.dot(m.stress);
        const Vector3 u(face_displacements[q][0], face_displacements[q][1], face_displacements[q][2]);
        const FrictionResponse t = coulomb_friction(normal, wall_point->traction,
                                                    u - wall_point->displacement, pressure, mu, penalty);
        wall_point->material.new_stress = m.stress;
        wall_point->material.new_strain = strain;
        wall_point->material.new_region = m.region;
        wall_point->new_traction = t.traction;
        wall_point->new_displacement = u;
        wall_point->new_slipping = t.slipping;
        wall_point->new_pressure = pressure;
        if (mu == 0.0) continue;
        fill_shape_matrices(fe_face_values, q);
        const double JxW = fe_face_values.JxW(q);
        // dp/du_j = -(n (x) n) : D : eps(phi_j), a row through the material tangent.
        const Eigen::Matrix<double, 1, Eigen::Dynamic> dp =
            -(m.tangent.transpose() * normal_projector).transpose() * B;
        cell_matrix.noalias() -=
            N.transpose() * (t.d_traction_d_displacement * N + t.d_traction_d_pressure * dp) * JxW;
        cell_rhs.noalias() += N.transpose() * t.traction * JxW;
      }
    }
    for (unsigned int i = 0; i < n; ++i) {
      local_rhs(i) = cell_rhs(i);
      for (unsigned int j = 0; j < n; ++j) local_matrix(i, j) = cell_matrix(i, j);
    }
    constraints.distribute_local_to_global(local_matrix, local_rhs, dofs, system_matrix_, system_rhs_);
  }
  system_matrix_.compress(VectorOperation::add);
  system_rhs_.compress(VectorOperation::add);
}

// GMRES (the tangent is not symmetric where walls slip or the flow is non-associated)
// preconditioned by smoothed-aggregation AMG as in elastic_column.cc (column_amg.h). Inexact Newton: the
// linear residual is reduced by min(1e-2, |r|/|f|) (Eisenstat & Walker 1996, SIAM J. Sci.
// Comput. 17:16; Kelley 1995, Iterative Methods for Linear and Nonlinear Equations, ch. 6),
// which keeps Newton's quadratic convergence while sparing GMRES iterations far from the
// solution; it need not go below 1e-3 of the Newton tolerance.
unsigned int FrictionalColumn::solve_linear_system(const AffineConstraints<double>& constraints,
                                                   const double relative_residual,
                                                   LA::MPI::Vector& newton_update) {
  TimerOutput::Scope timer_section(timer_, "solve");
  LA::MPI::PreconditionAMG preconditioner;
  initialize_column_amg(preconditioner, system_matrix_, dof_handler_, fe_.degree);

  const double rhs_norm = system_rhs_.l2_norm();
  const double target =
      std::max(std::min(1e-2, relative_residual) * rhs_norm, 1e-3 * problem_.newton.tolerance * load_norm_);
  SolverControl control(1000, target);
  // Right preconditioning, so that GMRES measures the true residual |b - K du| (left
  // preconditioning would measure |P^-1 (b - K du)|, a different unit).
  SolverGMRES<LA::MPI::Vector> gmres(
      control, SolverGMRES<LA::MPI::Vector>::AdditionalData(50, /*right_preconditioning=*/true));
  LA::MPI::Vector distributed_update(locally_owned_dofs_, comm_);
  constraints.set_zero(distributed_update);
  gmres.solve(system_matrix_, distributed_update, system_rhs_, preconditioner);
  constraints.distribute(distributed_update);
  newton_update = distributed_update;
  return control.last_step();
}

// Newton's method for one load step, from the converged state of the last one. A step
// that moves walls starts with the linearised step that carries the walls' displacement
// increment into the column (the only iteration with inhomogeneous constraints); every
// later iteration corrects with homogeneous ones. Returns false, leaving the state
// uncommitted, when Newton fails: too many iterations, a residual that explodes, or GMRES
// that does not converge (a nearly singular tangent, as perfect plasticity can give when a
// step is large).
bool FrictionalColumn::newton(const double load_factor, const std::array<double, 2>& wall_increment,
                              LoadStepLog& log) {
  LA::MPI::Vector start(locally_owned_dofs_, comm_), trial(locally_owned_dofs_, comm_);
  LA::MPI::Vector update;
  // u <- u_start + alpha du, with u_start the iterate the step was computed at.
  const auto move_to = [&](const LA::MPI::Vector& du, double alpha) {
    trial = start;
    trial.add(alpha, du);
    locally_relevant_solution_ = trial;
  };
  try {
    if (wall_increment[0] != 0.0 || wall_increment[1] != 0.0) {
      AffineConstraints<double> moving;
      make_constraints(moving, wall_increment, top_layer_);
      assemble_system(load_factor, moving);
      log.linear_iterations.push_back(solve_linear_system(moving, 1.0, update));
      start = locally_relevant_solution_;
      move_to(update, 1.0);
    }
    assemble_system(load_factor, newton_constraints_);
    double residual = system_rhs_.l2_norm() / load_norm_;
    for (unsigned int iteration = 0;; ++iteration) {
      log.residuals.push_back(residual);
      pcout_ << "    load step " << result_.load_steps.size() + 1 << ", Newton iteration " << iteration
             << ": |r|/|f| = " << residual << std::endl;
      if (residual <= problem_.newton.tolerance) return true;
      if (iteration == problem_.newton.max_iterations || !(residual < 1e6)) return false;
      log.linear_iterations.push_back(solve_linear_system(newton_constraints_, residual, update));
      // Backtracking line search on |r| (Dennis & Schnabel 1996, Numerical Methods for
      // Unconstrained Optimization and Nonlinear Equations, sect. 6.3): halve the step
      // while the residual grows, at most four times. Near the solution the full step
      // always decreases |r|, so the quadratic convergence is untouched; far from it (points
      // crossing between elastic, cone and apex, walls between stick and slip) it keeps
      // an overshooting step from throwing the iterate away.
      start = locally_relevant_solution_;
      for (double alpha = 1.0;; alpha *= 0.5) {
        move_to(update, alpha);
        assemble_system(load_factor, newton_constraints_);
        const double trial_residual = system_rhs_.l2_norm() / load_norm_;
        if (trial_residual < residual || alpha <= 1.0 / 16.0) {
          residual = trial_residual;
          break;
        }
        pcout_ << "      line search: |r|/|f| = " << trial_residual << " at step " << alpha << std::endl;
      }
    }
  } catch (const SolverControl::NoConvergence& e) {
    pcout_ << "    GMRES did not converge: residual " << e.last_residual << " after " << e.last_step
           << " iterations" << std::endl;
    return false;
  }
}

// One load step; if Newton fails, the step is cut in two halves, each solved the same way,
// down to 1/16 of the step. A layer of staged construction is placed whole: it cannot be
// cut.
void FrictionalColumn::solve_load_step(const double from, const double to,
                                       const std::array<double, 2>& wall_increment,
                                       const unsigned int depth) {
  const LA::MPI::Vector start = locally_relevant_solution_;
  LoadStepLog log;
  if (newton(to, wall_increment, log)) {
    commit_state();
    for (const unsigned int its : log.linear_iterations) result_.linear_iterations += its;
    result_.newton_iterations += log.linear_iterations.size();
    result_.load_steps.push_back(std::move(log));
    return;
  }
  const bool divisible = from != to || wall_increment[0] != 0.0 || wall_increment[1] != 0.0;
  if (depth == 4 || !divisible) {
    std::ostringstream m;
    m << "Newton's method did not converge in load step " << result_.load_steps.size() + 1
      << " of the frictional column (load factor " << to << ", " << depth
      << " bisections of the step); |r|/|f| "
      << "per iteration:";
    for (const double r : log.residuals) m << ' ' << r;
    throw NewtonFailure(m.str());
  }
  pcout_ << "    load step " << result_.load_steps.size() + 1 << " failed: bisected" << std::endl;
  ++result_.bisections;
  locally_relevant_solution_ = start;
  const double middle = 0.5 * (from + to);
  const std::array<double, 2> half = {0.5 * wall_increment[0], 0.5 * wall_increment[1]};
  solve_load_step(from, middle, half, depth + 1);
  solve_load_step(middle, to, half, depth + 1);
}

// The last assembly evaluated every point at the converged u: keep it.
void FrictionalColumn::commit_state() {
  for (auto& p : material_points_) p.commit();
  for (auto& p : wall_points_) p.commit();
}

// Staged construction: the cells of `layer` start stress-free in the column's current
// shape, so only what happens after their placement strains them; their dofs not shared
// with the column below start at zero displacement.
void FrictionalColumn::place_layer(const unsigned int layer) {
  top_layer_ = layer;
  make_constraints(newton_constraints_, {0.0, 0.0}, top_layer_);
  FEValues<dim> fe_values(fe_, quadrature_, update_gradients);
  FEFaceValues<dim> fe_face_values(fe_, face_quadrature_, update_values | update_gradients);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<SymmetricTensor<2, dim>> strains(quadrature_.size()), face_strains(face_quadrature_.size());
  std::vector<Tensor<1, dim>> face_displacements(face_quadrature_.size());
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned() || layer_of(cell) != layer) continue;
    fe_values.reinit(cell);
    fe_values[displacement].get_function_symmetric_gradients(locally_relevant_solution_, strains);
    for (unsigned int q = 0; q < quadrature_.size(); ++q)
      material_points_[cell->active_cell_index() * quadrature_.size() + q].place(mandel_of(strains[q]));
    auto wall_point = wall_points_of(cell);
    for (const unsigned int f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary() || cell->face(f)->boundary_id() >= n_walls) continue;
      fe_face_values.reinit(cell, f);
      fe_face_values[displacement].get_function_symmetric_gradients(locally_relevant_solution_, face_strains);
      fe_face_values[displacement].get_function_values(locally_relevant_solution_, face_displacements);
      for (unsigned int q = 0; q < face_quadrature_.size(); ++q, ++wall_point)
        wall_point->place(
            mandel_of(face_strains[q]),
            Vector3(face_displacements[q][0], face_displacements[q][1], face_displacements[q][2]));
    }
  }
}

// Coarse-cell averages of sigma, the walls' and the floor's vertical forces, the slipping
// wall area and the plastic volume, all from the committed state.
void FrictionalColumn::postprocess() {
  FEValues<dim> fe_values(fe_, quadrature_, update_JxW_values);
  FEFaceValues<dim> fe_face_values(fe_, face_quadrature_, update_JxW_values | update_quadrature_points);
  const unsigned int n_q = quadrature_.size();
  column_mesh::CoarseStressIntegrals coarse_integrals(problem_.column);
  const unsigned int levels = problem_.column.cells[2];
  const double level_height = problem_.column.height / levels;
  std::vector<double> by_level(levels, 0.0);
  for (auto& v : cell_stress_) v.reinit(triangulation_.n_active_cells());
  cell_plastic_share_.reinit(triangulation_.n_active_cells());
  // wall force, floor force, slipping area, frictional loaded area, plastic volume, volume
  std::array<double, 6> sums = {};
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    const MaterialPoint* points = &material_points_[cell->active_cell_index() * n_q];
    Vec6 integral = Vec6::Zero();
    double plastic = 0.0;
    for (unsigned int q = 0; q < n_q; ++q) {
      integral += points[q].stress * fe_values.JxW(q);
      if (points[q].region != ReturnRegion::elastic) plastic += fe_values.JxW(q);
    }
    const SymmetricTensor<2, dim> sigma = symmetric_tensor_of(integral);
    coarse_integrals.add(cell->center(), sigma);
    for (unsigned int k = 0; k < 6; ++k) {
      const auto [i, j] = column_mesh::stress_components[k];
      cell_stress_[k][cell->active_cell_index()] = sigma[i][j] / cell->measure();
    }
    cell_plastic_share_[cell->active_cell_index()] = plastic / cell->measure();
    sums[4] += plastic;
    sums[5] += cell->measure();

    auto wall_point = wall_points_of(cell);
    for (const unsigned int f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary() || cell->face(f)->boundary_id() >= n_walls) continue;
      const types::boundary_id wall = cell->face(f)->boundary_id();
      fe_face_values.reinit(cell, f);
      for (unsigned int q = 0; q < face_quadrature_.size(); ++q, ++wall_point) {
        const double JxW = fe_face_values.JxW(q);
        if (wall == column_mesh::floor_z0) {
          sums[1] -= wall_point->material.stress[2] * JxW;  // the floor pushes up with -sigma_zz
          continue;
        }
        sums[0] += wall_point->traction[2] * JxW;
        const double z = fe_face_values.quadrature_point(q)[2];
        const auto level = static_cast<unsigned int>(std::clamp(z / level_height, 0.0, levels - 1.0));
        by_level[level] += wall_point->traction[2] * JxW;
        if (problem_.walls.side[wall] > 0.0 && wall_point->pressure > 0.0) {
          sums[3] += JxW;
          if (wall_point->slipping) sums[2] += JxW;
        }
      }
    }
  }
  const std::vector<double> local(sums.begin(), sums.end());
  std::vector<double> global(local.size());
  Utilities::MPI::sum(local, comm_, global);
  result_.side_wall_vertical_force = global[0];
  result_.floor_vertical_force = global[1];
  result_.slipping_wall_share = global[3] > 0.0 ? global[2] / global[3] : 0.0;
  result_.plastic_volume_share = global[4] / global[5];
  result_.side_wall_vertical_force_by_level.resize(levels);
  Utilities::MPI::sum(by_level, comm_, result_.side_wall_vertical_force_by_level);
  const ColumnProblem& c = problem_.column;
  result_.weight = c.density * c.gravity * c.length_x * c.length_y * c.height;
  result_.cell_average_stress = coarse_integrals.averages(comm_);
}

// As elastic_column.cc writes its column, with the share of each cell's volume that
// yielded in the last step.
void FrictionalColumn::output_results(const std::string& folder) const {
  column_mesh::write_column(dof_handler_, locally_relevant_solution_, cell_stress_,
                            {{"plastic_share", &cell_plastic_share_}}, folder, comm_);
}

FrictionalColumnSolution FrictionalColumn::run(const std::string& vtu_folder) {
  Timer total(comm_, /*sync_lap_times=*/true);
  {
    TimerOutput::Scope t(timer_, "setup");
    make_grid();
    setup_system();
    setup_quadrature_point_history();
    load_norm_ = gravity_load_norm();
  }
  const ColumnLoading& loading = problem_.loading;
  if (loading.staged_construction) {
    for (unsigned int layer = 0; layer < n_layers_; ++layer) {
      if (layer > 0) place_layer(layer);
      solve_load_step(1.0, 1.0, {0.0, 0.0}, 0);
    }
  } else {
    for (unsigned int step = 1; step <= loading.load_steps; ++step)
      solve_load_step(static_cast<double>(step - 1) / loading.load_steps,
                      static_cast<double>(step) / loading.load_steps, {0.0, 0.0}, 0);
  }
  const bool relax = loading.wall_displacement[0] > 0.0 || loading.wall_displacement[1] > 0.0;
  for (unsigned int step = 1; relax && step <= loading.relaxation_steps; ++step)
    solve_load_step(1.0, 1.0,
                    {loading.wall_displacement[0] / loading.relaxation_steps,
                     loading.wall_displacement[1] / loading.relaxation_steps},
                    0);
  {
    TimerOutput::Scope t(timer_, "postprocess");
    postprocess();
  }
  if (!vtu_folder.empty()) {
    TimerOutput::Scope t(timer_, "output");
    output_results(vtu_folder);
  }
  const std::map<std::string, double> times = timer_.get_summary_data(TimerOutput::total_wall_time);
  result_.assemble_seconds = times.count("assemble") ? times.at("assemble") : 0.0;
  result_.solve_seconds = times.count("solve") ? times.at("solve") : 0.0;
  result_.total_seconds = total.wall_time();
  return result_;
}

}  // namespace

FrictionalColumnSolution solve_frictional_column(const FrictionalColumnProblem& problem, MPI_Comm comm,
                                                 const std::string& vtu_folder) {
  validate(problem);  // before any communication, so every rank throws alike
  column_mesh::silence_p4est();
  FrictionalColumnSolution solution = FrictionalColumn(problem, comm).run(vtu_folder);
  // As in solve_column: release deal.II's pooled GMRES vectors before MPI_Finalize can.
  GrowingVectorMemory<LA::MPI::Vector>::release_unused_memory();
  return solution;
}

}  // namespace upgrain::fem
