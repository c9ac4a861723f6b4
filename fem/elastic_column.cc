// The only translation unit of upgrain::fem that includes deal.II (each one costs ~25 s
// and 1.5 GB to compile). It follows the structure of deal.II's step-8 (vector-valued
// elasticity) and step-40 (distributed mesh, Trilinos, AMG): one class whose run() calls
// make_grid() -> setup_system() -> assemble_system() -> solve() -> postprocess() ->
// output_results(), each timed by TimerOutput. The BVP and its exact solution are in
// fem/analytic/confined_column.h and docs/fem.md.
#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/generic_linear_algebra.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/lac/vector_memory.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <map>

#include "fem/column_amg.h"
#include "fem/column_mesh.h"
#include "fem/elastic_column.h"

namespace upgrain::fem {

namespace {

using namespace dealii;
namespace LA = dealii::LinearAlgebraTrilinos;

using column_mesh::dim;
using column_mesh::floor_z0, column_mesh::wall_x0, column_mesh::wall_x1, column_mesh::wall_y0,
    column_mesh::wall_y1;

// The exact displacement (0, 0, u_z(z)), eq. (3) of confined_column.h, for
// VectorTools::integrate_difference.
class ExactDisplacement : public Function<dim> {
 public:
  explicit ExactDisplacement(const ConfinedColumn& column) : Function<dim>(dim), column_(column) {}
  double value(const Point<dim>& p, const unsigned int component) const override {
    return component == 2 ? column_.vertical_displacement(p[2]) : 0.0;
  }
  void vector_value(const Point<dim>& p, Vector<double>& values) const override {
    for (unsigned int c = 0; c < dim; ++c) values[c] = value(p, c);
  }

 private:
  ConfinedColumn column_;
};

class ElasticColumn {
 public:
  ElasticColumn(const ColumnProblem& problem, MPI_Comm comm);
  ColumnSolution run(const std::string& vtu_folder);

 private:
  void make_grid();
  void setup_system();
  void assemble_system();
  void solve();
  void postprocess();
  void output_results(const std::string& folder) const;

  // Hooke's law for an isotropic solid: sigma = lambda tr(eps) 1 + 2 mu eps.
  SymmetricTensor<2, dim> stress(const SymmetricTensor<2, dim>& strain) const {
    return lambda_ * trace(strain) * unit_symmetric_tensor<dim>() + 2.0 * mu_ * strain;
  }
  // Eq. (1)-(2) of confined_column.h: diag(K0, K0, 1) sigma_zz(z).
  SymmetricTensor<2, dim> exact_stress(const double z) const {
    const double s = exact_.vertical_stress(z);
    SymmetricTensor<2, dim> sigma;
    sigma[0][0] = sigma[1][1] = exact_.k0() * s;
    sigma[2][2] = s;
    return sigma;
  }
  void keep_point_stress(const Point<dim>& x, double weight, const SymmetricTensor<2, dim>& sigma) {
    QuadratureStress& out = result_.quadrature_stress;
    out.x.push_back({x[0], x[1], x[2]});
    out.weight.push_back(weight);
    std::array<double, 9> s{};
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j) s[dim * i + j] = sigma[i][j];
    out.sigma.push_back(s);
  }

  const ColumnProblem problem_;
  const ConfinedColumn exact_;
  const double lambda_, mu_;
  MPI_Comm comm_;

  parallel::distributed::Triangulation<dim> triangulation_;
  const FESystem<dim> fe_;
  DoFHandler<dim> dof_handler_;
  IndexSet locally_owned_dofs_;
  IndexSet locally_relevant_dofs_;
  AffineConstraints<double> constraints_;

  LA::MPI::SparseMatrix system_matrix_;
  LA::MPI::Vector locally_relevant_solution_;
  LA::MPI::Vector system_rhs_;

  // Volume average of sigma over each locally owned active cell, for output only;
  // components xx, yy, zz, xy, xz, yz.
  std::array<Vector<double>, 6> cell_stress_;

  ColumnSolution result_;
  TimerOutput timer_;
};

ElasticColumn::ElasticColumn(const ColumnProblem& problem, MPI_Comm comm)
    : problem_(problem),
      exact_(analytic_solution(problem)),
      lambda_(exact_.lame_lambda()),
      mu_(exact_.shear_modulus()),
      comm_(comm),
      triangulation_(comm),
      fe_(FE_Q<dim>(problem.degree), dim),
      dof_handler_(triangulation_),
      // The library prints nothing: the caller gets the times in ColumnSolution. No
      // communicator: its destructor would otherwise try to synchronise (and print a
      // warning) while an exception thrown on all ranks unwinds the stack.
      timer_(std::cout, TimerOutput::never, TimerOutput::wall_times) {}

void ElasticColumn::make_grid() { column_mesh::make_grid(triangulation_, problem_); }

void ElasticColumn::setup_system() {
  dof_handler_.distribute_dofs(fe_);
  locally_owned_dofs_ = dof_handler_.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler_, locally_relevant_dofs_);

  locally_relevant_solution_.reinit(locally_owned_dofs_, locally_relevant_dofs_, comm_);
  system_rhs_.reinit(locally_owned_dofs_, comm_);

  // Frictionless rollers: only the normal displacement is constrained on each wall and on
  // the floor, so the walls carry no shear traction (the exact solution has none). The top
  // stays free. Edges and corners get one constraint per wall they belong to.
  constraints_.clear();
  constraints_.reinit(locally_relevant_dofs_);
  DoFTools::make_hanging_node_constraints(dof_handler_, constraints_);
  const Functions::ZeroFunction<dim> zero(dim);
  const std::pair<types::boundary_id, unsigned int> rollers[] = {
      {wall_x0, 0}, {wall_x1, 0}, {wall_y0, 1}, {wall_y1, 1}, {floor_z0, 2}};
  for (const auto& [boundary, component] : rollers)
    if (!(problem_.open_side_x1 && boundary == wall_x1))
      VectorTools::interpolate_boundary_values(dof_handler_, boundary, zero, constraints_,
                                               fe_.component_mask(FEValuesExtractors::Scalar(component)));
  constraints_.close();

  DynamicSparsityPattern dsp(locally_relevant_dofs_);
  DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints_, /*keep_constrained_dofs=*/false);
  SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs_, comm_, locally_relevant_dofs_);
  system_matrix_.reinit(locally_owned_dofs_, locally_owned_dofs_, dsp, comm_);

  result_.n_dofs = dof_handler_.n_dofs();
  result_.n_active_cells = triangulation_.n_global_active_cells();
}

// The weak form of -div sigma(u) = f (step-8): for all test functions v,
//   a(u, v) = int lambda (div u)(div v) + 2 mu eps(u) : eps(v) dx = int f . v dx,
// with f = (0, 0, -rho g). The top is traction free, so there is no boundary term.
void ElasticColumn::assemble_system() {
  // Q_k shape gradients are polynomials of degree k per variable, so the products in
  // a(u, v) have degree 2k per variable: Gauss with k + 1 points is exact.
  const QGauss<dim> quadrature(fe_.degree + 1);
  FEValues<dim> fe_values(fe_, quadrature, update_values | update_gradients | update_JxW_values);

  const unsigned int dofs_per_cell = fe_.n_dofs_per_cell();
  FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell);
  Vector<double> cell_rhs(dofs_per_cell);
  std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);

  // Shape-function data at one quadrature point, evaluated once and reused in the double
  // loop below.
  const FEValuesExtractors::Vector displacement(0);
  std::vector<SymmetricTensor<2, dim>> eps_phi(dofs_per_cell);
  std::vector<double> div_phi(dofs_per_cell);
  std::vector<double> phi_z(dofs_per_cell);
  const double body_force_z = -problem_.density * problem_.gravity;

  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    cell_matrix = 0.0;
    cell_rhs = 0.0;
    fe_values.reinit(cell);

    for (const unsigned int q : fe_values.quadrature_point_indices()) {
      for (unsigned int k = 0; k < dofs_per_cell; ++k) {
        eps_phi[k] = fe_values[displacement].symmetric_gradient(k, q);
        div_phi[k] = fe_values[displacement].divergence(k, q);
        phi_z[k] = fe_values[displacement].value(k, q)[2];
      }
      const double JxW = fe_values.JxW(q);
      // a(u, v) is symmetric: fill the lower triangle, mirror below.
      for (unsigned int i = 0; i < dofs_per_cell; ++i) {
        for (unsigned int j = 0; j <= i; ++j)
          cell_matrix(i, j) +=
              (lambda_ * div_phi[i] * div_phi[j] + 2.0 * mu_ * (eps_phi[i] * eps_phi[j])) * JxW;
        cell_rhs(i) += phi_z[i] * body_force_z * JxW;
      }
    }
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      for (unsigned int j = i + 1; j < dofs_per_cell; ++j) cell_matrix(i, j) = cell_matrix(j, i);

    cell->get_dof_indices(local_dof_indices);
    constraints_.distribute_local_to_global(cell_matrix, cell_rhs, local_dof_indices, system_matrix_,
                                            system_rhs_);
  }
  system_matrix_.compress(VectorOperation::add);
  system_rhs_.compress(VectorOperation::add);
}

// CG (the matrix is symmetric positive definite once the rollers remove the rigid modes)
// preconditioned by smoothed-aggregation AMG (Trilinos ML, column_amg.h), as in step-40 and step-42.
void ElasticColumn::solve() {
  LA::MPI::PreconditionAMG preconditioner;
  initialize_column_amg(preconditioner, system_matrix_, dof_handler_, fe_.degree);

  // The solver's tolerance (docs/fem.md, "Solver"): relative residual 1e-12. Q2 reproduces the quadratic
  // exact solution, so the solver tolerance is the only error left in that case.
  SolverControl control(dof_handler_.n_dofs(), 1e-12 * system_rhs_.l2_norm());
  SolverCG<LA::MPI::Vector> cg(control);
  LA::MPI::Vector distributed_solution(locally_owned_dofs_, comm_);
  cg.solve(system_matrix_, distributed_solution, system_rhs_, preconditioner);
  constraints_.distribute(distributed_solution);
  locally_relevant_solution_ = distributed_solution;
  result_.cg_iterations = control.last_step();
}

// Errors against the exact solution and the coarse-cell stress averages that the DEM
// comparison needs.
void ElasticColumn::postprocess() {
  // Displacement: ||u_h - u||_L2 by deal.II; Gauss with k + 2 points per direction is more
  // than enough for (u_h - u)^2, which has degree 2k per variable.
  const QGauss<dim> error_quadrature(fe_.degree + 2);
  // double, not the customary float: float cell errors limit the global error to ~1e-7
  // relative, which hides what the Q1 tests check (exact interpolation errors).
  Vector<double> difference_per_cell(triangulation_.n_active_cells());
  const ExactDisplacement exact_displacement(exact_);
  VectorTools::integrate_difference(dof_handler_, locally_relevant_solution_, exact_displacement,
                                    difference_per_cell, error_quadrature, VectorTools::L2_norm);
  result_.l2_error_displacement =
      VectorTools::compute_global_error(triangulation_, difference_per_cell, VectorTools::L2_norm);

  // Stress: one loop for the L2 error and the cell integrals. sigma_h has degree <= k per
  // variable and the exact sigma is linear, so Gauss with k + 1 points integrates both the
  // averages and the squared error exactly.
  const QGauss<dim> quadrature(fe_.degree + 1);
  FEValues<dim> fe_values(fe_, quadrature, update_gradients | update_quadrature_points | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<SymmetricTensor<2, dim>> strains(quadrature.size());

  column_mesh::CoarseStressIntegrals coarse_integrals(problem_);
  double squared_stress_error = 0.0;
  for (auto& v : cell_stress_) v.reinit(triangulation_.n_active_cells());

  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    fe_values[displacement].get_function_symmetric_gradients(locally_relevant_solution_, strains);
    SymmetricTensor<2, dim> cell_integral;
    for (const unsigned int q : fe_values.quadrature_point_indices()) {
      const SymmetricTensor<2, dim> sigma = stress(strains[q]);
      const SymmetricTensor<2, dim> error = sigma - exact_stress(fe_values.quadrature_point(q)[2]);
      // SymmetricTensor's double contraction counts each off-diagonal entry twice: this is
      // the Frobenius norm of the full 3x3 tensor.
      squared_stress_error += (error * error) * fe_values.JxW(q);
      cell_integral += sigma * fe_values.JxW(q);
      if (problem_.keep_quadrature_stress)
        keep_point_stress(fe_values.quadrature_point(q), fe_values.JxW(q), sigma);
    }
    coarse_integrals.add(cell->center(), cell_integral);

    const unsigned int c = cell->active_cell_index();
    const double volume = cell->measure();
    for (unsigned int k = 0; k < 6; ++k) {
      const auto [i, j] = column_mesh::stress_components[k];
      cell_stress_[k][c] = cell_integral[i][j] / volume;
    }
  }

  result_.l2_error_stress = std::sqrt(Utilities::MPI::sum(squared_stress_error, comm_));
  result_.cell_average_stress = coarse_integrals.averages(comm_);
}

// Displacement, the cell averages of sigma and the subdomain, written by every rank
// (column_mesh::write_column: atomic pieces, the .pvtu record last).
void ElasticColumn::output_results(const std::string& folder) const {
  column_mesh::write_column(dof_handler_, locally_relevant_solution_, cell_stress_, {}, folder, comm_);
}

ColumnSolution ElasticColumn::run(const std::string& vtu_folder) {
  Timer total(comm_, /*sync_lap_times=*/true);
  {
    TimerOutput::Scope t(timer_, "setup");
    make_grid();
    setup_system();
  }
  {
    TimerOutput::Scope t(timer_, "assemble");
    assemble_system();
  }
  {
    TimerOutput::Scope t(timer_, "solve");
    solve();
  }
  {
    TimerOutput::Scope t(timer_, "postprocess");
    postprocess();
  }
  if (!vtu_folder.empty()) {
    TimerOutput::Scope t(timer_, "output");
    output_results(vtu_folder);
  }
  const std::map<std::string, double> times = timer_.get_summary_data(TimerOutput::total_wall_time);
  result_.setup_seconds = times.at("setup");
  result_.assemble_seconds = times.at("assemble");
  result_.solve_seconds = times.at("solve");
  result_.total_seconds = total.wall_time();
  return result_;
}

}  // namespace

ColumnSolution solve_column(const ColumnProblem& problem, MPI_Comm comm, const std::string& vtu_folder) {
  validate(problem);  // before any communication, so every rank throws alike
  column_mesh::silence_p4est();
  ColumnSolution solution = ElasticColumn(problem, comm).run(vtu_folder);
  // SolverCG takes its vectors from deal.II's static GrowingVectorMemory pool, which keeps
  // them (and their Epetra communicators) alive after this call. Release them now: freed
  // after MPI_Finalize they would abort. deal.II's MPI_InitFinalize does the same.
  GrowingVectorMemory<LA::MPI::Vector>::release_unused_memory();
  return solution;
}

}  // namespace upgrain::fem
