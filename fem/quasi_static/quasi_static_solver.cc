// The quasi-static continuum whose material is a state per quadrature point (docs/femxdem.md,
// "The continuum"). It reads like deal.II's step-18 (a history per quadrature point, load steps)
// and step-42 (Newton's method on the points' tangents, Trilinos, p4est): per load step the
// platens move, and each Newton iteration hands every point the trial displacement gradient from
// its last converged state, assembles the points' stresses and tangents, and solves for the
// correction. The points are committed only when the step converges; a step that fails is retried
// with half its increment. deal.II is confined to this translation unit.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/quadrature_point_data.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "dem/files/atomic_file.h"
#include "fem/column_mesh.h"
#include "fem/pvtu_pieces.h"
#include "fem/quasi_static/quasi_static_problem.h"

namespace upgrain::fem {

namespace {

using namespace dealii;
using DistributedVector = TrilinosWrappers::MPI::Vector;

// The point's history in deal.II's CellDataStorage: its state, its latest answer, and the answer
// it was committed with (the predictor's stress and tangent, and what the output shows).
struct PointRecord {
  std::unique_ptr<PointState> state;
  PointResponse response;
  Mat3x3 displacement_gradient = Mat3x3::Zero();  // of the latest trial
  PointResponse committed_response;
  Mat3x3 committed_gradient = Mat3x3::Zero();
  // The stress of its first answer, taken as balanced when the body force follows the load
  // (QuasiStaticProblem::body_force_follows_load): the loads then act on the change from it.
  Vec6 initial_stress = Vec6::Zero();
  double step_cost = 0.0;  // its answers' cost in the load step so far (the partition's weight)
};

// The symmetric gradient of a vector shape function as a Mandel vector (plane strain: the z
// components zero).
template <int dim>
Vec6 mandel_strain(const Tensor<2, dim>& grad) {
  Mat3x3 h = Mat3x3::Zero();
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) h(i, j) = grad[i][j];
  return mandel::from_matrix(0.5 * (h + h.transpose()));
}

// deal.II writes a cell's id as "coarse_children:" (CellId::to_string); without the trailing
// colon, a message can go on after it.
std::string place_name(std::string id) {
  if (!id.empty() && id.back() == ':') id.pop_back();
  return id;
}

template <int dim>
Mat3x3 padded(const Tensor<2, dim>& grad) {
  Mat3x3 h = Mat3x3::Zero();
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) h(i, j) = grad[i][j];
  return h;
}

// Which displacement components a face's support prescribes.
bool prescribes(const FaceCondition& f, int face_axis, int component) {
  switch (f.support) {
    case FaceSupport::fixed:
    case FaceSupport::rough_platen:
    case FaceSupport::affine:
      return true;
    case FaceSupport::roller:
    case FaceSupport::smooth_platen:
      return component == face_axis;
    case FaceSupport::free:
    case FaceSupport::pressure:
      return false;
  }
  return false;
}

bool is_platen(const FaceCondition& f) {
  return f.support == FaceSupport::smooth_platen || f.support == FaceSupport::rough_platen;
}

// u = G x on a face that follows a homogeneous displacement gradient G.
template <int dim>
class AffineDisplacement : public Function<dim> {
 public:
  explicit AffineDisplacement(const Mat3x3& g) : Function<dim>(dim), g_(g) {}
  double value(const Point<dim>& x, const unsigned component) const override {
    double u = 0.0;
    for (int j = 0; j < dim; ++j) u += g_(component, j) * x[j];
    return u;
  }

 private:
  Mat3x3 g_;
};

// A cell's points as p4est carries them (repartition_by_cost(), save()), packed by deal.II's
// Utilities::pack: the cell's cost, its weight in the last repartition by cost (0: none yet), per
// point its committed stress, tangent and displacement gradient (kPointNumbers numbers), and each
// point's state as its own bytes.
struct CellPack {
  static constexpr std::size_t kPointNumbers = 6 + 36 + 9;
  // Those of a problem whose points keep their initial stress (the 6 of it after them).
  static std::size_t point_numbers(const QuasiStaticProblem& p) {
    return kPointNumbers + (p.body_force_follows_load ? 6 : 0);
  }
  double cost = 0.0;
  unsigned weight = 0;
  std::vector<double> numbers;
  std::vector<std::vector<char>> states;
  template <class Archive>
  void serialize(Archive& archive, const unsigned int /*version*/) {
    archive& cost& weight& numbers& states;
  }
};

}  // namespace

// A load step's record in a checkpoint (boost's serialization finds it by its type's namespace).
template <class Archive>
void serialize(Archive& archive, LoadStepRecord& r, const unsigned int /*version*/) {
  archive& r.step& r.platen_displacement& r.platen_force& r.newton_iterations& r.residuals& r.cuts& r
      .line_search_halvings& r.cost& r.imbalance& r.repartitioned& r.seconds;
}

namespace {

// Every parameter that fixes the path of a problem, in words: a checkpoint of one problem does not
// continue another.
std::string problem_key(const QuasiStaticProblem& p) {
  std::ostringstream k;
  k.precision(17);
  k << p.dimension << ';';
  for (int d = 0; d < 3; ++d) k << p.size[d] << ',' << p.cells[d] << ';';
  k << p.degree << ';' << p.quadrature_points << ';';
  for (const FaceCondition& f : p.faces) k << static_cast<int>(f.support) << ',' << f.pressure << ';';
  k << p.density << ';' << p.gravity[0] << ',' << p.gravity[1] << ',' << p.gravity[2] << ';'
    << p.platen_displacement << ';';
  for (int i = 0; i < 9; ++i) k << p.boundary_gradient.data()[i] << ',';
  k << ';' << p.load_steps << ';' << p.residual_tolerance << ';' << p.correction_tolerance << ';'
    << p.max_newton_iterations << ';' << p.line_search_halvings << ';' << p.max_step_cuts << ';'
    << p.rebalance_threshold;
  // Written only when set: the checkpoints of problems that apply the body force at step 0 keep
  // their key.
  if (p.body_force_follows_load) k << ";body force follows the load";
  return k.str();
}

// What a checkpoint holds besides the mesh's files (stem.solver): where the loading stands.
struct SavedRun {
  static constexpr const char* kHead = "Upgrain quasi-static state 1\n";
  std::string problem;  // problem_key()
  unsigned ranks = 0;
  unsigned points_handle = 0;  // of the points' bytes among the mesh's attached data
  double committed_lambda = 0.0;
  double achievable = 1.0;  // the last repartition's weights over its partition
  std::vector<LoadStepRecord> steps;
  std::vector<std::string> pvd_entries, measure_names;
  template <class Archive>
  void serialize(Archive& archive, const unsigned int /*version*/) {
    archive& problem& ranks& points_handle& committed_lambda& achievable& steps& pvd_entries& measure_names;
  }
};

// The step's failure: which point (or Newton), on every rank the same words.
struct StepFailure {
  bool failed = false;
  std::string what;
};

// The ranks agreed on a stop request inside a step (QuasiStaticCheckpoints::stop_requested).
struct StopAgreed {};

template <int dim>
class QuasiStaticSolver {
 public:
  QuasiStaticSolver(const QuasiStaticProblem& p, const PointFactory& make_point, MPI_Comm comm,
                    const QuasiStaticOutput& output, const QuasiStaticCheckpoints& checkpoints)
      : p_(p),
        make_point_(make_point),
        comm_(comm),
        output_(output),
        checkpoints_(checkpoints),
        triangulation_(comm),
        fe_(FE_Q<dim>(p.degree), dim),
        dofs_(triangulation_),
        quadrature_(p.quadrature_points > 0 ? p.quadrature_points : p.degree + 1),
        face_quadrature_(p.degree + 1) {}

  QuasiStaticResult run();

 private:
  void make_mesh();
  void setup_system();
  void make_points();
  // The point `q` of `cell` made by the factory; `fv` must have been reinitialised on the cell.
  std::unique_ptr<PointState> make_point(FEValues<dim>& fv,
                                         const typename Triangulation<dim>::cell_iterator& cell,
                                         unsigned q) const;
  // The busiest rank's cost in the step over the ranks' mean, and the least a partition into
  // whole cells can reach: the costliest cell's over the mean (collective).
  std::pair<double, double> imbalance() const;
  // Collective: repartitions the mesh with each cell weighted by its points' cost in the step,
  // moving the points (PointState::save and load) and the committed displacement with their cells.
  // Returns the imbalance of those costs over the new partition: the best whole cells allow
  // (p4est cuts its space-filling curve into contiguous pieces).
  double repartition_by_cost();
  // Collective: repartitions the mesh by the locally owned cells' `weights` (p4est cuts its
  // space-filling curve where the weights' running sum crosses equal shares, whatever the current
  // partition), moving the points and the committed displacement with their cells. Returns the
  // busiest rank's cost (CellPack::cost) over the mean after the move.
  double move_cells(const std::map<CellId, unsigned>& weights);
  // A locally owned cell's points as bytes (CellPack, packed): per point its committed stress,
  // tangent and displacement gradient, then its state (PointState::save). Adds their step cost to
  // `cost`; a point that cannot be saved leaves its words in `failure`.
  std::vector<char> pack_cell(const typename Triangulation<dim>::cell_iterator& cell, double& cost,
                              std::string& failure) const;
  // The points of a cell this rank now owns, from pack_cell()'s bytes: made by the factory at
  // their place and loaded. Adds the cost the bytes carry to `cost`; a failure leaves its words.
  void unpack_cell(const typename Triangulation<dim>::cell_iterator& cell,
                   const boost::iterator_range<std::vector<char>::const_iterator>& data, FEValues<dim>& fv,
                   double& cost, std::string& failure);
  // Collective: the whole state under `stem` (QuasiStaticCheckpoints).
  void save(const std::string& stem, const std::vector<LoadStepRecord>& steps, double achievable);
  // Collective: the state saved under `stem`, into the coarse mesh make_mesh() made.
  SavedRun resume(const std::string& stem);
  // Collective: the words of the lowest rank whose `local_failure` is not empty, on every rank
  // (empty when none has one), so that a failure on one rank stops all of them in step instead of
  // leaving the others waiting in the next collective call; and the same, thrown.
  std::string first_failure(const std::string& local_failure) const;
  void throw_first_failure(const std::string& local_failure) const;
  // The prescribed values of u at the load factor `lambda` (0 at step 0, 1 at the end).
  std::map<types::global_dof_index, double> boundary_values(double lambda) const;
  // Assembles at u_trial_: every point answers; fills the residual and the matrix with the
  // constrained rows taken out by `constraints`. Returns the relative out-of-balance force, or a
  // failure. `committed`: the points' committed answers instead, with no new trial (the
  // predictor, at the converged state).
  double assemble(const AffineConstraints<double>& constraints, bool committed, StepFailure& failure);
  // The correction's constraints with the prescribed values' change from `from` to `to` as their
  // inhomogeneities.
  AffineConstraints<double> increment_constraints(double from, double to) const;
  StepFailure newton(double lambda, LoadStepRecord& record);
  void commit(double lambda);
  double platen_force() const;
  void write_step(unsigned step);
  std::vector<PointSummary> point_summaries() const;
  // This rank's points: each one's place and committed state.
  std::vector<std::pair<PointPlace, const PointState*>> owned_points() const;
  // Calls visit(place, record) for each point of the locally owned cells, in the cells' order.
  template <class Visit>
  void for_each_owned_point(const Visit& visit) const;

  QuasiStaticProblem p_;
  PointFactory make_point_;
  MPI_Comm comm_;
  QuasiStaticOutput output_;
  QuasiStaticCheckpoints checkpoints_;
  parallel::distributed::Triangulation<dim> triangulation_;
  FESystem<dim> fe_;
  DoFHandler<dim> dofs_;
  QGauss<dim> quadrature_;
  QGauss<dim - 1> face_quadrature_;
  IndexSet owned_, relevant_;
  AffineConstraints<double> update_constraints_;  // the correction's: zero where u is prescribed
  IndexSet platen_dofs_;                          // the normal components on the platens
  std::map<types::global_dof_index, double> platen_sign_;
  TrilinosWrappers::SparseMatrix matrix_;
  DistributedVector u_committed_, u_trial_, residual_, internal_full_, external_full_;
  CellDataStorage<typename Triangulation<dim>::cell_iterator, PointRecord> history_;
  double cost_ = 0.0;  // this rank's points' cost since the last record
  double committed_lambda_ = 0.0;
  double body_force_factor_ = 1.0;  // of the body force, at the load factor being solved for
  bool committed_answers_ = false;  // the points have answered at the committed state
  std::vector<std::string> pvd_entries_;
  std::vector<std::string> measure_names_;  // the points' PointState::measures(), every rank's
  // The locally owned cells' weights in the last repartition by cost (empty: none yet, p4est's
  // even split by cells), carried with the cells and kept by a checkpoint: a restart partitions
  // by them again.
  std::map<CellId, unsigned> partition_weight_;
};

template <int dim>
void QuasiStaticSolver<dim>::make_mesh() {
  std::vector<unsigned int> repetitions(dim);
  Point<dim> hi;
  for (int d = 0; d < dim; ++d) {
    repetitions[d] = p_.cells[d];
    hi[d] = p_.size[d];
  }
  GridGenerator::subdivided_hyper_rectangle(triangulation_, repetitions, Point<dim>(), hi, /*colorize=*/true);
}

template <int dim>
std::map<types::global_dof_index, double> QuasiStaticSolver<dim>::boundary_values(double lambda) const {
  std::map<types::global_dof_index, double> values;
  for (unsigned face = 0; face < 2 * dim; ++face) {
    const FaceCondition& f = p_.faces[face];
    const int axis = static_cast<int>(face / 2);
    const double outward = face % 2 == 0 ? -1.0 : 1.0;
    std::vector<bool> mask(dim, false);
    dealii::Vector<double> value(dim);
    bool any = false;
    for (int c = 0; c < dim; ++c) {
      if (!prescribes(f, axis, c)) continue;
      mask[c] = any = true;
      if (is_platen(f) && c == axis) value[c] = outward * lambda * p_.platen_displacement;
    }
    if (!any) continue;
    if (f.support == FaceSupport::affine)
      VectorTools::interpolate_boundary_values(dofs_, static_cast<types::boundary_id>(face),
                                               AffineDisplacement<dim>(lambda * p_.boundary_gradient),
                                               values);
    else
      VectorTools::interpolate_boundary_values(dofs_, static_cast<types::boundary_id>(face),
                                               Functions::ConstantFunction<dim>(value), values,
                                               ComponentMask(mask));
  }
  return values;
}

template <int dim>
void QuasiStaticSolver<dim>::setup_system() {
  dofs_.distribute_dofs(fe_);
  owned_ = dofs_.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dofs_, relevant_);

  update_constraints_.clear();
  update_constraints_.reinit(relevant_);
  for (const auto& [dof, value] : boundary_values(0.0)) {
    (void)value;
    if (relevant_.is_element(dof)) update_constraints_.add_line(dof);
  }
  // Components that no face holds would leave rigid motions free: pin them at the origin's
  // vertex, and a rotation in the plane of two such components at the vertex along the first.
  std::array<bool, 3> held{false, false, false};
  for (unsigned face = 0; face < 2 * dim; ++face)
    for (int c = 0; c < dim; ++c)
      held[c] = held[c] || prescribes(p_.faces[face], static_cast<int>(face / 2), c);
  std::vector<std::pair<Point<dim>, int>> pins;
  for (int c = 0; c < dim; ++c)
    if (!held[c]) pins.emplace_back(Point<dim>(), c);
  for (int a = 0; a < dim; ++a)
    for (int b = a + 1; b < dim; ++b)
      if (!held[a] && !held[b]) {
        Point<dim> corner;
        corner[a] = p_.size[a];
        pins.emplace_back(corner, b);
      }
  const double tolerance = 1e-10 * *std::max_element(p_.size.begin(), p_.size.begin() + dim);
  for (const auto& cell : dofs_.active_cell_iterators()) {
    if (cell->is_artificial()) continue;
    for (const unsigned v : cell->vertex_indices())
      for (const auto& [x, c] : pins)
        if (cell->vertex(v).distance(x) < tolerance) {
          const auto dof = cell->vertex_dof_index(v, c);
          if (!update_constraints_.is_constrained(dof)) update_constraints_.add_line(dof);
        }
  }
  update_constraints_.close();

  platen_dofs_ = IndexSet(dofs_.n_dofs());
  platen_sign_.clear();
  for (unsigned face = 0; face < 2 * dim; ++face) {
    if (!is_platen(p_.faces[face])) continue;
    std::vector<bool> mask(dim, false);
    mask[face / 2] = true;
    const IndexSet on_face =
        DoFTools::extract_boundary_dofs(dofs_, ComponentMask(mask), {static_cast<types::boundary_id>(face)});
    for (const auto dof : on_face) platen_sign_[dof] = face % 2 == 0 ? -1.0 : 1.0;
    platen_dofs_.add_indices(on_face);
  }

  DynamicSparsityPattern dsp(relevant_);
  DoFTools::make_sparsity_pattern(dofs_, dsp, update_constraints_, false);
  SparsityTools::distribute_sparsity_pattern(dsp, owned_, comm_, relevant_);
  matrix_.reinit(owned_, owned_, dsp, comm_);
  for (DistributedVector* v : {&u_committed_, &residual_, &internal_full_, &external_full_})
    v->reinit(owned_, comm_);
  u_trial_.reinit(owned_, comm_);
}

template <int dim>
void QuasiStaticSolver<dim>::make_points() {
  FEValues<dim> fv(fe_, quadrature_, update_quadrature_points);
  std::string made;  // this rank's first failure
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    history_.initialize(cell, quadrature_.size());
    fv.reinit(cell);
    auto records = history_.get_data(cell);
    for (unsigned q = 0; q < quadrature_.size() && made.empty(); ++q) {
      try {
        records[q]->state = make_point(fv, cell, q);
        records[q]->state->start();
      } catch (const std::exception& e) {
        made = e.what();
      }
    }
  }
  throw_first_failure(made);
  // The measures' names, from any point (a rank may own no cell); every point must give the same,
  // checked here on every rank together so that a mismatch stops them all with the same words.
  std::vector<std::string> local;
  for (const auto& cell : triangulation_.active_cell_iterators())
    if (cell->is_locally_owned()) {
      for (const PointMeasure& m : history_.get_data(cell).front()->state->measures())
        local.push_back(m.name);
      break;
    }
  for (auto& names : Utilities::MPI::all_gather(comm_, local))
    if (!names.empty()) {
      measure_names_ = std::move(names);
      break;
    }
  std::string mismatch;
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    if (!cell->is_locally_owned() || !mismatch.empty()) continue;
    const auto records = history_.get_data(cell);
    for (unsigned q = 0; q < records.size() && mismatch.empty(); ++q) {
      std::vector<std::string> names;
      for (const PointMeasure& m : records[q]->state->measures()) names.push_back(m.name);
      if (names != measure_names_)
        mismatch = "quasi-static solver: the point " + std::to_string(q) + " of cell " +
                   place_name(cell->id().to_string()) + " has " + std::to_string(names.size()) +
                   " measures, another point " + std::to_string(measure_names_.size()) +
                   " (every point must name the same)";
    }
  }
  throw_first_failure(mismatch);
}

template <int dim>
std::unique_ptr<PointState> QuasiStaticSolver<dim>::make_point(
    FEValues<dim>& fv, const typename Triangulation<dim>::cell_iterator& cell, unsigned q) const {
  PointPlace place;
  place.cell = cell->id().to_string();
  place.index = q;
  for (int d = 0; d < dim; ++d) place.position[d] = fv.quadrature_point(q)[d];
  std::unique_ptr<PointState> made = make_point_(place);
  if (!made) throw std::runtime_error("quasi-static solver: no material made for cell " + place.cell);
  return made;
}

template <int dim>
std::pair<double, double> QuasiStaticSolver<dim>::imbalance() const {
  double costliest = 0.0;
  for (const auto& cell : triangulation_.active_cell_iterators())
    if (cell->is_locally_owned()) {
      double c = 0.0;
      for (const auto& r : history_.get_data(cell)) c += r->step_cost;
      costliest = std::max(costliest, c);
    }
  const double busiest = Utilities::MPI::max(cost_, comm_);
  costliest = Utilities::MPI::max(costliest, comm_);
  const double mean = Utilities::MPI::sum(cost_, comm_) / Utilities::MPI::n_mpi_processes(comm_);
  if (!(mean > 0.0)) return {1.0, 1.0};
  return {busiest / mean, std::max(costliest / mean, 1.0)};
}

template <int dim>
std::vector<char> QuasiStaticSolver<dim>::pack_cell(const typename Triangulation<dim>::cell_iterator& cell,
                                                    double& cost, std::string& failure) const {
  CellPack pack;
  if (const auto w = partition_weight_.find(cell->id()); w != partition_weight_.end())
    pack.weight = w->second;
  for (const auto& r : history_.get_data(cell)) {
    pack.cost += r->step_cost;
    const double* stress = r->committed_response.stress.data();
    const double* tangent = r->committed_response.tangent.data();
    const double* gradient = r->committed_gradient.data();
    pack.numbers.insert(pack.numbers.end(), stress, stress + 6);
    pack.numbers.insert(pack.numbers.end(), tangent, tangent + 36);
    pack.numbers.insert(pack.numbers.end(), gradient, gradient + 9);
    if (p_.body_force_follows_load)
      pack.numbers.insert(pack.numbers.end(), r->initial_stress.data(), r->initial_stress.data() + 6);
    try {
      pack.states.push_back(r->state->save());
    } catch (const std::exception& e) {
      if (failure.empty())
        failure = "the material at cell " + place_name(cell->id().to_string()) + ": " + e.what();
    }
  }
  cost += pack.cost;
  return Utilities::pack(pack, /*allow_compression=*/false);
}

template <int dim>
void QuasiStaticSolver<dim>::unpack_cell(const typename Triangulation<dim>::cell_iterator& cell,
                                         const boost::iterator_range<std::vector<char>::const_iterator>& data,
                                         FEValues<dim>& fv, double& cost, std::string& failure) {
  history_.initialize(cell, quadrature_.size());
  if (!failure.empty()) return;
  try {
    const auto pack = Utilities::unpack<CellPack>(data.begin(), data.end(), /*allow_compression=*/false);
    cost += pack.cost;
    if (pack.weight > 0) partition_weight_[cell->id()] = pack.weight;
    const auto records = history_.get_data(cell);
    if (pack.states.size() != records.size() ||
        pack.numbers.size() != CellPack::point_numbers(p_) * records.size())
      throw std::runtime_error("its bytes hold " + std::to_string(pack.states.size()) + " points, not " +
                               std::to_string(records.size()));
    fv.reinit(cell);
    for (unsigned q = 0; q < records.size(); ++q) {
      PointRecord& r = *records[q];
      const double* x = pack.numbers.data() + CellPack::point_numbers(p_) * q;
      std::copy(x, x + 6, r.committed_response.stress.data());
      std::copy(x + 6, x + 42, r.committed_response.tangent.data());
      std::copy(x + 42, x + 51, r.committed_gradient.data());
      if (p_.body_force_follows_load) std::copy(x + 51, x + 57, r.initial_stress.data());
      r.state = make_point(fv, cell, q);
      r.state->load(pack.states[q]);
      r.response = r.committed_response;
      r.displacement_gradient = r.committed_gradient;
    }
  } catch (const std::exception& e) {
    failure =
        "the material at cell " + place_name(cell->id().to_string()) + " could not be restored: " + e.what();
  }
}

template <int dim>
double QuasiStaticSolver<dim>::repartition_by_cost() {
  // p4est balances the sum of the weights: each cell's cost in the step in 1e6 parts of the
  // heaviest's, and one part more so that a cell that cost nothing still counts.
  std::map<CellId, double> cost;
  double heaviest = 0.0;
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    double c = 0.0;
    for (const auto& r : history_.get_data(cell)) c += r->step_cost;
    cost[cell->id()] = c;
    heaviest = std::max(heaviest, c);
  }
  heaviest = Utilities::MPI::max(heaviest, comm_);
  std::map<CellId, unsigned> weights;
  for (const auto& [id, c] : cost)
    weights[id] = 1u + static_cast<unsigned>(heaviest > 0.0 ? std::lround(1e6 * c / heaviest) : 0);
  return move_cells(weights);
}

template <int dim>
double QuasiStaticSolver<dim>::move_cells(const std::map<CellId, unsigned>& weights) {
  using CellIterator = typename Triangulation<dim>::cell_iterator;
  using CellStatus = typename Triangulation<dim>::CellStatus;
  partition_weight_ = weights;  // the cells carry their weights
  // Each local cell's points as bytes, made before the repartition so that a point that cannot be
  // saved stops every rank here, not inside p4est.
  std::map<CellId, std::vector<char>> packed;
  std::string failure;
  double cost = 0.0;
  for (const auto& cell : triangulation_.active_cell_iterators())
    if (cell->is_locally_owned()) packed[cell->id()] = pack_cell(cell, cost, failure);
  throw_first_failure(
      failure.empty() ? failure : "quasi-static solver: the ranks cannot be balanced by cost: " + failure);

  auto weight = triangulation_.signals.weight.connect(
      [&](const CellIterator& cell, CellStatus) -> unsigned { return weights.at(cell->id()); });
  const auto handle = triangulation_.register_data_attach(
      [&](const CellIterator& cell, CellStatus) { return packed.at(cell->id()); }, /*variable size*/ true);
  DistributedVector ghosted(owned_, relevant_, comm_);
  ghosted = u_committed_;
  parallel::distributed::SolutionTransfer<dim, DistributedVector> transfer(dofs_);
  transfer.prepare_for_coarsening_and_refinement(ghosted);
  triangulation_.repartition();
  weight.disconnect();
  packed.clear();

  history_.clear();
  partition_weight_.clear();
  setup_system();
  transfer.interpolate(u_committed_);
  u_trial_ = u_committed_;
  FEValues<dim> fv(fe_, quadrature_, update_quadrature_points);
  double moved_cost = 0.0;  // of this rank's cells now
  triangulation_.notify_ready_to_unpack(
      handle, [&](const CellIterator& cell, CellStatus,
                  const boost::iterator_range<std::vector<char>::const_iterator>& data) {
        unpack_cell(cell, data, fv, moved_cost, failure);
      });
  throw_first_failure(failure.empty() ? failure
                                      : "quasi-static solver: a cell moved to another rank: " + failure);
  const double mean = Utilities::MPI::sum(moved_cost, comm_) / Utilities::MPI::n_mpi_processes(comm_);
  return mean > 0.0 ? Utilities::MPI::max(moved_cost, comm_) / mean : 1.0;
}

template <int dim>
void QuasiStaticSolver<dim>::save(const std::string& stem, const std::vector<LoadStepRecord>& steps,
                                  double achievable) {
  using CellIterator = typename Triangulation<dim>::cell_iterator;
  using CellStatus = typename Triangulation<dim>::CellStatus;
  std::map<CellId, std::vector<char>> packed;
  std::string failure;
  double cost = 0.0;
  for (const auto& cell : triangulation_.active_cell_iterators())
    if (cell->is_locally_owned()) packed[cell->id()] = pack_cell(cell, cost, failure);
  throw_first_failure(failure.empty() ? failure
                                      : "quasi-static solver: the state cannot be saved: " + failure);
  SavedRun run;
  run.problem = problem_key(p_);
  run.ranks = Utilities::MPI::n_mpi_processes(comm_);
  // The points first, then the displacement: resume() unpacks them by these handles.
  run.points_handle = triangulation_.register_data_attach(
      [&](const CellIterator& cell, CellStatus) { return packed.at(cell->id()); }, /*variable size*/ true);
  DistributedVector ghosted(owned_, relevant_, comm_);
  ghosted = u_committed_;
  parallel::distributed::SolutionTransfer<dim, DistributedVector> transfer(dofs_);
  transfer.prepare_for_serialization(ghosted);
  triangulation_.save(stem);
  run.committed_lambda = committed_lambda_;
  run.achievable = achievable;
  run.steps = steps;
  run.pvd_entries = pvd_entries_;
  run.measure_names = measure_names_;
  std::string written;
  if (Utilities::MPI::this_mpi_process(comm_) == 0) {
    const std::vector<char> body = Utilities::pack(run, /*allow_compression=*/false);
    std::string bytes = SavedRun::kHead;
    bytes.append(body.begin(), body.end());
    try {
      dem::io::write_bytes(stem + ".solver", bytes.data(), bytes.size(), stem + ".solver");
    } catch (const std::exception& e) {
      written = std::string("quasi-static solver: ") + e.what();
    }
  }
  throw_first_failure(written);
}

template <int dim>
SavedRun QuasiStaticSolver<dim>::resume(const std::string& stem) {
  using CellIterator = typename Triangulation<dim>::cell_iterator;
  using CellStatus = typename Triangulation<dim>::CellStatus;
  // Where the loading stands first: a state of another problem is refused before p4est reads its
  // mesh.
  SavedRun run;
  std::string failure;
  try {
    std::ifstream in(stem + ".solver", std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::string head = SavedRun::kHead;
    if (!in.good() && !in.eof()) throw std::runtime_error("cannot be read");
    if (bytes.compare(0, head.size(), head) != 0) throw std::runtime_error("is not a state of this solver");
    const std::vector<char> body(bytes.begin() + static_cast<std::ptrdiff_t>(head.size()), bytes.end());
    run = Utilities::unpack<SavedRun>(body, /*allow_compression=*/false);
    if (run.problem != problem_key(p_))
      throw std::runtime_error(
          "is the state of another problem (its mesh, faces, loading or Newton parameters differ)");
    if (run.steps.empty()) throw std::runtime_error("holds no converged step");
  } catch (const std::exception& e) {
    failure = "quasi-static solver: " + stem + ".solver " + e.what();
  }
  throw_first_failure(failure);
  triangulation_.load(stem);
  setup_system();
  parallel::distributed::SolutionTransfer<dim, DistributedVector> transfer(dofs_);
  transfer.deserialize(u_committed_);
  u_trial_ = u_committed_;
  // Registered again, as deal.II's SolutionTransfer::deserialize does, so that the triangulation
  // counts this data set as unpacked and forgets its callbacks afterwards (a callback left over
  // would be called by the next repartition). Registered in the order of save(), it gets the
  // handle its bytes were saved under.
  const unsigned handle = triangulation_.register_data_attach(
      [](const CellIterator&, CellStatus) { return std::vector<char>(); }, /*variable size*/ true);
  if (handle != run.points_handle)
    throw std::logic_error("quasi-static solver: the points' data are not where save() put them");
  FEValues<dim> fv(fe_, quadrature_, update_quadrature_points);
  double cost = 0.0;
  triangulation_.notify_ready_to_unpack(
      handle, [&](const CellIterator& cell, CellStatus,
                  const boost::iterator_range<std::vector<char>::const_iterator>& data) {
        unpack_cell(cell, data, fv, cost, failure);
      });
  throw_first_failure(failure.empty() ? failure
                                      : "quasi-static solver: resuming from " + stem + ": " + failure);
  // p4est loads the cells split evenly; a run that was repartitioned by cost gets its partition
  // back from the same weights, and with it the same sums in the same order.
  if (Utilities::MPI::max(partition_weight_.empty() ? 0u : 1u, comm_) > 0) move_cells(partition_weight_);
  committed_lambda_ = run.committed_lambda;
  committed_answers_ = true;
  pvd_entries_ = run.pvd_entries;
  measure_names_ = run.measure_names;
  return run;
}

template <int dim>
std::string QuasiStaticSolver<dim>::first_failure(const std::string& local_failure) const {
  const unsigned ranks = Utilities::MPI::n_mpi_processes(comm_);
  const unsigned first =
      Utilities::MPI::min(local_failure.empty() ? ranks : Utilities::MPI::this_mpi_process(comm_), comm_);
  return first < ranks ? Utilities::MPI::broadcast(comm_, local_failure, first) : std::string();
}

template <int dim>
void QuasiStaticSolver<dim>::throw_first_failure(const std::string& local_failure) const {
  if (std::string what = first_failure(local_failure); !what.empty()) throw std::runtime_error(what);
}

template <int dim>
double QuasiStaticSolver<dim>::assemble(const AffineConstraints<double>& constraints, bool committed,
                                        StepFailure& failure) {
  DistributedVector ghosted(owned_, relevant_, comm_);
  ghosted = u_trial_;
  matrix_ = 0.0;
  residual_ = 0.0;
  internal_full_ = 0.0;
  external_full_ = 0.0;

  FEValues<dim> fv(fe_, quadrature_, update_gradients | update_values | update_JxW_values);
  FEFaceValues<dim> ffv(fe_, face_quadrature_, update_values | update_JxW_values | update_normal_vectors);
  const FEValuesExtractors::Vector u(0);
  const unsigned n = fe_.n_dofs_per_cell(), nq = quadrature_.size();
  FullMatrix<double> cell_matrix(n, n);
  dealii::Vector<double> cell_internal(n), cell_external(n), cell_residual(n);
  std::vector<types::global_dof_index> local(n);
  std::vector<Tensor<2, dim>> grads(nq);
  std::vector<Vec6> shape_strain(n);
  // The body force per unit density at the load factor of the state assembled.
  Tensor<1, dim> gravity;
  for (int d = 0; d < dim; ++d) gravity[d] = body_force_factor_ * p_.gravity[d];
  std::string local_failure;

  for (const auto& cell : dofs_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fv.reinit(cell);
    cell->get_dof_indices(local);
    cell_matrix = 0.0;
    cell_internal = 0.0;
    cell_external = 0.0;
    fv[u].get_function_gradients(ghosted, grads);
    const auto records = history_.get_data(typename Triangulation<dim>::cell_iterator(cell));
    for (unsigned q = 0; q < nq; ++q) {
      PointRecord& r = *records[q];
      if (!committed && local_failure.empty()) {
        r.displacement_gradient = padded<dim>(grads[q]);
        // With the size of the increment it was asked for: whether a point fails a large trial (a
        // predictor or correction that concentrates the strain) or a small one tells the remedy.
        const auto where = [&] {
          char increment[64];
          std::snprintf(increment, sizeof increment, "%.3g",
                        (r.displacement_gradient - r.committed_gradient).cwiseAbs().maxCoeff());
          return "the material at point " + std::to_string(q) + " of cell " +
                 place_name(cell->id().to_string()) + " (trial increment max |dH_ij| = " + increment + ")";
        };
        // A point that cannot take its trial at all (an inverted element: det F <= 0) fails the step
        // like one that does not converge, on this rank alone: the other ranks learn it below,
        // instead of waiting in the next collective call for a rank that threw.
        try {
          r.response = r.state->respond(r.displacement_gradient);
          // Step 0's answers, before anything is committed: the initial stresses.
          if (p_.body_force_follows_load && !committed_answers_) r.initial_stress = r.response.stress;
          cost_ += r.response.cost;
          r.step_cost += r.response.cost;
          if (!r.response.converged) local_failure = where() + " did not converge: " + r.response.failure;
        } catch (const std::exception& e) {
          local_failure = where() + " refused its trial: " + e.what();
        }
      }
      const PointResponse& answer = committed ? r.committed_response : r.response;
      const double jxw = fv.JxW(q);
      const Tensor<1, dim> body = r.state->density().value_or(p_.density) * gravity;
      const Vec6 stress = p_.body_force_follows_load ? Vec6(answer.stress - r.initial_stress) : answer.stress;
      for (unsigned i = 0; i < n; ++i) shape_strain[i] = mandel_strain<dim>(fv[u].gradient(i, q));
      for (unsigned i = 0; i < n; ++i) {
        cell_internal(i) += stress.dot(shape_strain[i]) * jxw;
        cell_external(i) += fv[u].value(i, q) * body * jxw;
        const Vec6 d_eps = answer.tangent.transpose() * shape_strain[i];
        for (unsigned j = 0; j < n; ++j) cell_matrix(i, j) += d_eps.dot(shape_strain[j]) * jxw;
      }
    }
    for (const unsigned f : cell->face_indices()) {
      if (!cell->at_boundary(f)) continue;
      const FaceCondition& c = p_.faces[cell->face(f)->boundary_id()];
      // With the initial stresses taken as balanced, the constant pressures are in them.
      if (c.support != FaceSupport::pressure || p_.body_force_follows_load) continue;
      ffv.reinit(cell, f);
      for (unsigned q = 0; q < face_quadrature_.size(); ++q)
        for (unsigned i = 0; i < n; ++i)
          cell_external(i) += -c.pressure * (ffv[u].value(i, q) * ffv.normal_vector(q)) * ffv.JxW(q);
    }
    for (unsigned i = 0; i < n; ++i) cell_residual(i) = cell_external(i) - cell_internal(i);
    internal_full_.add(local, cell_internal);
    external_full_.add(local, cell_external);
    constraints.distribute_local_to_global(cell_matrix, cell_residual, local, matrix_, residual_);
  }
  matrix_.compress(VectorOperation::add);
  for (DistributedVector* v : {&residual_, &internal_full_, &external_full_})
    v->compress(VectorOperation::add);

  // A stop request abandons the step before its answers, which may have been cut short, are used.
  if (checkpoints_.stop_requested && Utilities::MPI::max(checkpoints_.stop_requested() ? 1 : 0, comm_) > 0)
    throw StopAgreed{};
  failure.what = first_failure(local_failure);
  if (!failure.what.empty()) {
    failure.failed = true;
    return 0.0;
  }
  const double reference = std::max(internal_full_.l2_norm(), external_full_.l2_norm());
  return reference > 0.0 ? residual_.l2_norm() / reference : 0.0;
}

template <int dim>
AffineConstraints<double> QuasiStaticSolver<dim>::increment_constraints(double from, double to) const {
  AffineConstraints<double> c;
  c.reinit(relevant_);
  for (const auto& line : update_constraints_.get_lines()) c.add_line(line.index);
  const auto before = boundary_values(from);
  for (const auto& [dof, value] : boundary_values(to))
    if (c.is_constrained(dof)) c.set_inhomogeneity(dof, value - before.at(dof));
  c.close();
  return c;
}

template <int dim>
StepFailure QuasiStaticSolver<dim>::newton(double lambda, LoadStepRecord& record) {
  DistributedVector step_increment(owned_, comm_), correction(owned_, comm_), start(owned_, comm_);
  SolverControl control(1, 0);
  TrilinosWrappers::SolverDirect solver(control,
                                        TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
  const auto solve = [&](const AffineConstraints<double>& constraints) {
    try {
      solver.solve(matrix_, correction, residual_);
    } catch (const dealii::ExceptionBase& e) {
      throw std::runtime_error(
          "quasi-static solver: the linear solve failed (KLU): the stiffness matrix is singular, a mode that "
          "no face and no point's tangent holds");
    }
    constraints.distribute(correction);
  };
  record.residuals.clear();
  body_force_factor_ = p_.body_force_follows_load ? lambda : 1.0;
  u_trial_ = u_committed_;
  StepFailure failure;
  if (committed_answers_) {
    // The predictor: the converged state's tangent, and the prescribed values' change as the
    // correction's inhomogeneous constraints, so that the whole mesh, not only the elements along
    // the platens, takes the step's first strain (as deal.II's step-44 applies its Dirichlet
    // increments). The points answer nothing new. It is not shortened: the prescribed values must
    // be reached whole, and a predictor that asks too much of a point fails the step, which is cut.
    const AffineConstraints<double> predictor = increment_constraints(committed_lambda_, lambda);
    assemble(predictor, true, failure);
    solve(predictor);
    u_trial_ += correction;
  } else {
    for (const auto& [dof, value] : boundary_values(lambda))
      if (owned_.is_element(dof)) u_trial_[dof] = value;
    u_trial_.compress(VectorOperation::insert);
  }
  double r = assemble(update_constraints_, false, failure);
  if (failure.failed) return failure;
  double norm = residual_.l2_norm();
  bool small_correction = false;
  for (unsigned it = 0;; ++it) {
    record.residuals.push_back(r);
    record.newton_iterations = it;
    if (r <= p_.residual_tolerance || small_correction) return {};
    // Nothing is applied at step 0 of a body force that follows the load: the points' first
    // answers are the start (QuasiStaticProblem::body_force_follows_load).
    if (lambda == 0.0 && p_.body_force_follows_load) return {};
    if (it == p_.max_newton_iterations)
      return {true, "Newton's method did not converge in " + std::to_string(it) +
                        " iterations: out-of-balance force " + std::to_string(r) + " of the internal force"};
    solve(update_constraints_);
    step_increment = u_trial_;
    step_increment -= u_committed_;
    step_increment.add(1.0, correction);
    const double scale = step_increment.l2_norm();
    small_correction = p_.correction_tolerance > 0.0 && scale > 0.0 &&
                       correction.l2_norm() <= p_.correction_tolerance * scale;

    // Backtracking along the correction (Dennis & Schnabel 1996, Numerical Methods for
    // Unconstrained Optimization and Nonlinear Equations, sec. 6.5): u + a du for a = 1, 1/2, ...,
    // the first that every point can answer and that decreases the out-of-balance force,
    // ||R(a)|| <= (1 - 1e-4 a) ||R(0)||. Past a softening peak a full correction can overshoot
    // into strains a point cannot take (a DEM cell's runaway overlap) or away from the balance.
    // A correction that already meets the correction criterion is taken whole: there the force
    // left is the points' noise. If no fraction decreases the force, the one that left the least
    // is taken (plain Newton when the full one did); if no fraction can be answered at all, the
    // step fails and is cut.
    start = u_trial_;
    double alpha = 1.0, best_alpha = 0.0, best_norm = std::numeric_limits<double>::infinity();
    StepFailure last_failure;
    bool accepted = false;
    for (unsigned h = 0; h <= p_.line_search_halvings && !accepted; ++h, alpha /= 2.0) {
      if (h > 0) ++record.line_search_halvings;
      u_trial_ = start;
      u_trial_.add(alpha, correction);
      last_failure = {};
      r = assemble(update_constraints_, false, last_failure);
      if (last_failure.failed) continue;
      const double trial_norm = residual_.l2_norm();
      accepted = small_correction || trial_norm <= (1.0 - 1e-4 * alpha) * norm;
      if (trial_norm < best_norm) {
        best_norm = trial_norm;
        best_alpha = alpha;
      }
      if (accepted) norm = trial_norm;
    }
    if (accepted) continue;
    if (best_alpha == 0.0) return last_failure;
    if (best_alpha != 2.0 * alpha) {  // the points hold the last fraction's answers: ask again
      u_trial_ = start;
      u_trial_.add(best_alpha, correction);
      r = assemble(update_constraints_, false, failure);
      if (failure.failed) return failure;
    }
    norm = best_norm;
  }
}

template <int dim>
void QuasiStaticSolver<dim>::commit(double lambda) {
  for (const auto& cell : triangulation_.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const auto& r : history_.get_data(cell)) {
        r->state->commit();
        r->committed_response = r->response;
        r->committed_gradient = r->displacement_gradient;
      }
  u_committed_ = u_trial_;
  committed_lambda_ = lambda;
  committed_answers_ = true;
}

template <int dim>
double QuasiStaticSolver<dim>::platen_force() const {
  double sum = 0.0;
  for (const auto& [dof, sign] : platen_sign_)
    if (owned_.is_element(dof)) sum += sign * (internal_full_[dof] - external_full_[dof]);
  unsigned platens = 0;
  for (unsigned face = 0; face < 2 * dim; ++face) platens += is_platen(p_.faces[face]) ? 1 : 0;
  return Utilities::MPI::sum(sum, comm_) / std::max(platens, 1u);
}

template <int dim>
void QuasiStaticSolver<dim>::write_step(unsigned step) {
  if (output_.folder.empty()) return;
  const unsigned n_cells = triangulation_.n_active_cells();
  std::array<dealii::Vector<double>, 6> stress, strain;
  for (unsigned k = 0; k < 6; ++k) {
    stress[k].reinit(n_cells);
    strain[k].reinit(n_cells);
  }
  dealii::Vector<double> mean_pressure(n_cells), deviator(n_cells), stress_ratio(n_cells);
  std::vector<dealii::Vector<double>> measures(measure_names_.size(), dealii::Vector<double>(n_cells));
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    Vec6 s = Vec6::Zero(), e = Vec6::Zero();
    const auto records = history_.get_data(cell);
    const unsigned c = cell->active_cell_index();
    for (const auto& r : records) {
      s += r->committed_response.stress;
      e += mandel::from_matrix(0.5 * (r->committed_gradient + r->committed_gradient.transpose()));
      const std::vector<PointMeasure> m = r->state->measures();
      for (std::size_t k = 0; k < measures.size() && k < m.size(); ++k)
        measures[k][c] += m[k].value / static_cast<double>(records.size());
    }
    s /= static_cast<double>(records.size());
    e /= static_cast<double>(records.size());
    const Mat3x3 sm = mandel::to_matrix(s), em = mandel::to_matrix(e);
    for (unsigned k = 0; k < 6; ++k) {
      const auto [i, j] = column_mesh::stress_components[k];
      stress[k][c] = sm(i, j);
      strain[k][c] = em(i, j);
    }
    mean_pressure[c] = -mandel::trace(s) / 3.0;
    deviator[c] = std::sqrt(1.5) * mandel::deviator(s).norm();
    stress_ratio[c] = mean_pressure[c] != 0.0 ? deviator[c] / mean_pressure[c] : 0.0;
  }
  DataOut<dim> out;
  out.attach_dof_handler(dofs_);
  DistributedVector ghosted(owned_, relevant_, comm_);
  ghosted = u_committed_;
  const std::vector<std::string> names(dim, "displacement");
  const std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds(
      dim, DataComponentInterpretation::component_is_part_of_vector);
  out.add_data_vector(ghosted, names, DataOut<dim>::type_dof_data, kinds);
  static const std::array<const char*, 6> strain_names = {"eps_xx", "eps_yy", "eps_zz",
                                                          "eps_xy", "eps_xz", "eps_yz"};
  for (unsigned k = 0; k < 6; ++k) {
    out.add_data_vector(stress[k], column_mesh::stress_names[k], DataOut<dim>::type_cell_data);
    out.add_data_vector(strain[k], strain_names[k], DataOut<dim>::type_cell_data);
  }
  out.add_data_vector(mean_pressure, "p", DataOut<dim>::type_cell_data);
  out.add_data_vector(deviator, "q", DataOut<dim>::type_cell_data);
  out.add_data_vector(stress_ratio, "q_over_p", DataOut<dim>::type_cell_data);
  for (std::size_t k = 0; k < measures.size(); ++k)
    out.add_data_vector(measures[k], measure_names_[k], DataOut<dim>::type_cell_data);
  dealii::Vector<float> subdomain(n_cells);
  for (auto& s : subdomain) s = static_cast<float>(triangulation_.locally_owned_subdomain());
  out.add_data_vector(subdomain, "subdomain");
  out.build_patches(p_.degree);
  const std::string name = output_.name + "-" + Utilities::int_to_string(step, 4);
  write_pieces_and_record(out, output_.folder, name, comm_);
  pvd_entries_.push_back(name + ".pvtu");
  if (Utilities::MPI::this_mpi_process(comm_) == 0) {
    std::ostringstream pvd;
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
    for (std::size_t k = 0; k < pvd_entries_.size(); ++k)
      pvd << "<DataSet timestep=\"" << k << "\" file=\"" << pvd_entries_[k] << "\"/>\n";
    pvd << "</Collection>\n</VTKFile>\n";
    dem::io::write_text_atomically(std::filesystem::path(output_.folder) / (output_.name + ".pvd"),
                                   pvd.str());
  }
}

template <int dim>
template <class Visit>
void QuasiStaticSolver<dim>::for_each_owned_point(const Visit& visit) const {
  FEValues<dim> fv(fe_, quadrature_, update_quadrature_points);
  for (const auto& cell : triangulation_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fv.reinit(cell);
    const auto records = history_.get_data(cell);
    for (unsigned q = 0; q < records.size(); ++q) {
      PointPlace place;
      place.cell = cell->id().to_string();
      place.index = q;
      for (int d = 0; d < dim; ++d) place.position[d] = fv.quadrature_point(q)[d];
      visit(place, *records[q]);
    }
  }
}

template <int dim>
std::vector<std::pair<PointPlace, const PointState*>> QuasiStaticSolver<dim>::owned_points() const {
  std::vector<std::pair<PointPlace, const PointState*>> out;
  for_each_owned_point(
      [&](const PointPlace& place, const PointRecord& r) { out.emplace_back(place, r.state.get()); });
  return out;
}

template <int dim>
std::vector<PointSummary> QuasiStaticSolver<dim>::point_summaries() const {
  using Packed = std::pair<std::string, std::vector<double>>;
  std::vector<Packed> local;
  for_each_owned_point([&](const PointPlace& place, const PointRecord& r) {
    std::vector<double> v{static_cast<double>(place.index)};
    for (int d = 0; d < 3; ++d) v.push_back(place.position[d]);
    for (int k = 0; k < 6; ++k) v.push_back(r.committed_response.stress[k]);
    for (int k = 0; k < 9; ++k) v.push_back(r.committed_gradient(k / 3, k % 3));
    v.push_back(r.state->density().value_or(p_.density));
    // As many as named (make_points() checked that every point names the same).
    const std::vector<PointMeasure> m = r.state->measures();
    for (std::size_t k = 0; k < measure_names_.size(); ++k)
      v.push_back(k < m.size() ? m[k].value : std::nan(""));
    local.emplace_back(place.cell, std::move(v));
  });
  std::vector<Packed> all;
  for (auto& part : Utilities::MPI::all_gather(comm_, local)) all.insert(all.end(), part.begin(), part.end());
  std::sort(all.begin(), all.end(), [](const Packed& a, const Packed& b) {
    const CellId ca(a.first), cb(b.first);
    return ca == cb ? a.second[0] < b.second[0] : ca < cb;
  });
  std::vector<PointSummary> out;
  for (const auto& [id, v] : all) {
    PointSummary s;
    s.place.cell = id;
    s.place.index = static_cast<unsigned>(v[0]);
    for (int d = 0; d < 3; ++d) s.place.position[d] = v[1 + d];
    for (int k = 0; k < 6; ++k) s.stress[k] = v[4 + k];
    for (int k = 0; k < 9; ++k) s.displacement_gradient(k / 3, k % 3) = v[10 + k];
    s.density = v[19];
    s.measures.assign(v.begin() + 20, v.end());
    out.push_back(s);
  }
  return out;
}

template <int dim>
QuasiStaticResult QuasiStaticSolver<dim>::run() {
  make_mesh();
  QuasiStaticResult result;
  double achievable = 1.0;  // the last repartition's weights over its partition
  if (checkpoints_.resume.empty()) {
    setup_system();
    make_points();
  } else {
    SavedRun saved = resume(checkpoints_.resume);
    result.steps = std::move(saved.steps);
    achievable = saved.achievable;
    if (checkpoints_.resumed) checkpoints_.resumed(result.steps);
  }
  if (!output_.folder.empty() && Utilities::MPI::this_mpi_process(comm_) == 0)
    std::filesystem::create_directories(output_.folder);

  result.n_dofs = dofs_.n_dofs();
  result.n_cells = triangulation_.n_global_active_cells();
  auto started = std::chrono::steady_clock::now();
  const auto record_step = [&](LoadStepRecord record, double lambda) {
    const auto now = std::chrono::steady_clock::now();
    record.seconds = Utilities::MPI::max(std::chrono::duration<double>(now - started).count(), comm_);
    started = now;
    record.platen_displacement = lambda * p_.platen_displacement;
    record.platen_force = platen_force();
    record.cost = Utilities::MPI::sum(cost_, comm_);
    const auto [imbalance_now, least] = imbalance();
    record.imbalance = imbalance_now;
    // Relative to what whole cells allow: the costliest cell's share, and the imbalance the last
    // repartition's own weights had over its partition (the same costs would give the same
    // partition again; costs that moved since then are worth another).
    if (p_.rebalance_threshold > 0.0 &&
        record.imbalance > p_.rebalance_threshold * std::max(achievable, least)) {
      achievable = repartition_by_cost();
      record.repartitioned = true;
    }
    cost_ = 0.0;
    for (const auto& cell : triangulation_.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto& r : history_.get_data(cell)) r->step_cost = 0.0;
    result.steps.push_back(std::move(record));
    write_step(result.steps.back().step);
    if (output_.on_step) output_.on_step(result.steps.back());
    if (output_.on_owned_points) output_.on_owned_points(result.steps.back(), owned_points());
    if (output_.on_points) output_.on_points(result.steps.back(), measure_names_, point_summaries());
    if (checkpoints_.stem)
      if (const std::string stem = checkpoints_.stem(result.steps.back()); !stem.empty()) {
        save(stem, result.steps, achievable);
        if (checkpoints_.saved) checkpoints_.saved(result.steps.back(), stem);
      }
  };

  // Asked to stop inside a step: the last converged step's state is saved now, as after that step
  // (the state committed since, part of an increment that was cut, goes with it and is continued
  // from; the step is done again whole).
  const auto stop_inside_step = [&](unsigned step) {
    if (result.steps.empty())
      throw std::runtime_error(
          "quasi-static solver: asked to stop during the equilibrium step 0: nothing to "
          "continue from");
    if (checkpoints_.stem)
      if (const std::string stem = checkpoints_.stem(result.steps.back()); !stem.empty()) {
        save(stem, result.steps, achievable);
        if (checkpoints_.saved) checkpoints_.saved(result.steps.back(), stem);
      }
    throw std::runtime_error("quasi-static solver: asked to stop during load step " + std::to_string(step) +
                             "; no state was saved to continue from");
  };

  // Step 0: the body force and the pressures on the points' initial stresses.
  if (result.steps.empty()) {
    LoadStepRecord record;
    StepFailure failure;
    try {
      failure = newton(0.0, record);
    } catch (const StopAgreed&) {
      stop_inside_step(0);
    }
    if (failure.failed) throw std::runtime_error("femxdem: the equilibrium step 0 failed: " + failure.what);
    commit(0.0);
    record_step(record, 0.0);
  }
  double reached = committed_lambda_;
  for (unsigned step = result.steps.back().step + 1; step <= p_.load_steps; ++step) {
    const double target = static_cast<double>(step) / p_.load_steps;
    LoadStepRecord record;
    record.step = step;
    double increment = target - reached;
    unsigned iterations = 0;
    while (reached != target) {
      const bool last = std::abs(increment) >= std::abs(target - reached);
      const double lambda = last ? target : reached + increment;
      StepFailure failure;
      try {
        failure = newton(lambda, record);
      } catch (const StopAgreed&) {
        stop_inside_step(step);
      }
      iterations += record.newton_iterations;
      if (!failure.failed) {
        commit(lambda);
        reached = lambda;
        continue;
      }
      if (++record.cuts > p_.max_step_cuts)
        throw std::runtime_error("femxdem: load step " + std::to_string(step) + " failed after " +
                                 std::to_string(p_.max_step_cuts) +
                                 " cuts of its increment: " + failure.what);
      increment /= 2.0;
    }
    record.newton_iterations = iterations;
    record_step(record, reached);
  }
  result.points = point_summaries();
  result.measure_names = measure_names_;
  return result;
}

}  // namespace

void validate(const QuasiStaticProblem& p) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (p.dimension != 2 && p.dimension != 3) fail("dimension must be 2 (plane strain) or 3");
  for (int d = 0; d < p.dimension; ++d) {
    if (!(p.size[d] > 0.0) || !std::isfinite(p.size[d]))
      fail("size along axis " + std::to_string(d) + " must be > 0");
    if (p.cells[d] == 0) fail("cells along axis " + std::to_string(d) + " must be >= 1");
  }
  if (p.degree < 1 || p.degree > 4) fail("degree must be 1 to 4");
  if (p.quadrature_points > 5) fail("quadrature points must be 0 (degree + 1) to 5 per direction");
  if (p.load_steps == 0) fail("load steps must be >= 1");
  if (p.line_search_halvings > 30) fail("line search halvings must be 0 (plain Newton) to 30");
  if (!(p.rebalance_threshold == 0.0 || p.rebalance_threshold >= 1.0))
    fail("the rebalance threshold must be 0 (never) or >= 1 (the busiest rank's cost over the mean)");
  if (!(p.residual_tolerance >= 0.0) || !(p.correction_tolerance >= 0.0))
    fail("the Newton tolerances must be >= 0");
  if (p.residual_tolerance == 0.0 && p.correction_tolerance == 0.0)
    fail("one of the Newton tolerances must be > 0");
  for (int f = 2 * p.dimension; f < 6; ++f)
    if (p.faces[f].support != FaceSupport::free) fail("a 2D problem has no faces along z");
  const bool affine = std::any_of(p.faces.begin(), p.faces.end(),
                                  [](const FaceCondition& f) { return f.support == FaceSupport::affine; });
  if (!p.boundary_gradient.isZero() && !affine)
    fail("a boundary gradient needs a face that follows it (affine)");
  if (p.platen_displacement != 0.0 &&
      std::none_of(p.faces.begin(), p.faces.end(), [](const FaceCondition& f) { return is_platen(f); }))
    fail("a platen displacement needs a face that is a platen");
}

QuasiStaticResult solve_quasi_static(const QuasiStaticProblem& problem, const PointFactory& make_point,
                                     MPI_Comm comm, const QuasiStaticOutput& output,
                                     const QuasiStaticCheckpoints& checkpoints) {
  validate(problem);
  column_mesh::silence_p4est();
  if (problem.dimension == 2)
    return QuasiStaticSolver<2>(problem, make_point, comm, output, checkpoints).run();
  return QuasiStaticSolver<3>(problem, make_point, comm, output, checkpoints).run();
}

}  // namespace upgrain::fem
